#include <pantocat/base/number_format.h>
#include <pantocat/scene/viscous_damping.h>

namespace pantocat
{
std::string ViscousDamping::name() const
{
  return "damping";
}

bool ViscousDamping::enabled(const SceneParameters& scene) const
{
  return scene.damping && (scene.carrier == WireModel::elastic ||
                           scene.contact_wire == WireModel::elastic);
}

void ViscousDamping::add_terms(SceneAssembly& a) const
{
  WireTerms t;
  for (const Wire wire : {Wire::carrier, Wire::contact_wire})
  {
    BlockOperator* body = a.body(wire == Wire::carrier ? "carrier" : "contact wire");
    if (body == nullptr)
      continue;
    t.damping =
        (wire == Wire::carrier ? a.catenary.carrier : a.catenary.contact_wire).damping;
    a.space.add_terms(wire, t, *body);
  }
}

std::string ViscousDamping::describe(const SceneAssembly& a) const
{
  return "damping: beta = " + number_to_string(a.catenary.carrier.damping) + ", " +
         number_to_string(a.catenary.contact_wire.damping) +
         " N s/m^2 (carrier, contact wire)";
}
} // namespace pantocat
