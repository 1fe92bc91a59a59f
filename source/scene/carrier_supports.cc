#include <pantocat/base/number_format.h>
#include <pantocat/scene/carrier_supports.h>

namespace pantocat
{
std::string CarrierSupports::name() const
{
  return "carrier supports";
}

bool CarrierSupports::enabled(const SceneParameters& scene,
                              const CatenaryParameters& catenary) const
{
  return scene.carrier == WireModel::elastic && catenary.number_of_spans() > 1;
}

void CarrierSupports::add_terms(SceneAssembly& a) const
{
  const CatenaryParameters& c = a.catenary();
  if (c.carrier_support != CarrierSupport::spring)
    return;
  const std::vector<double> x = c.interior_supports();
  for (unsigned int k = 0; k < x.size(); ++k)
  {
    a.add_point_spring(Wire::carrier, x[k], c.carrier_support_stiffness);
    if (k < c.carrier_support_preloads.size())
      a.add_point_force(Wire::carrier, x[k], c.carrier_support_preloads[k]);
  }
}

void CarrierSupports::add_constraints(SceneAssembly& a) const
{
  const CatenaryParameters& c = a.catenary();
  if (c.carrier_support != CarrierSupport::fixed)
    return;
  const std::vector<double> x = c.interior_supports();
  for (unsigned int k = 0; k < x.size(); ++k)
  {
    a.support_indices.push_back(a.system.n_constraints());
    a.system.add_constraint(std::make_unique<FixedConstraint>(
        a.constraint_name("carrier support " + std::to_string(k + 1)),
        Constraint::Kind::bilateral, a.wire_row(Wire::carrier, x[k]), 0.));
  }
}

std::string CarrierSupports::describe(const SceneAssembly& a) const
{
  const CatenaryParameters& c = a.catenary();
  const std::string n = std::to_string(c.interior_supports().size());
  return c.carrier_support == CarrierSupport::fixed
             ? n + " carrier supports, fixed (bilateral constraints)"
             : n + " carrier supports, springs k = " +
                   number_to_string(c.carrier_support_stiffness) + " N/m, preloaded";
}
} // namespace pantocat
