#include <pantocat/base/number_format.h>
#include <pantocat/scene/steady_arms.h>

namespace pantocat
{
std::string SteadyArms::name() const
{
  return "steady arms";
}

bool SteadyArms::enabled(const SceneParameters& scene,
                         const CatenaryParameters& catenary) const
{
  return scene.contact_wire == WireModel::elastic && catenary.number_of_spans() > 1 &&
         catenary.steady_arm_stiffness > 0.;
}

std::vector<double> SteadyArms::positions(const SceneParameters& scene,
                                          const CatenaryParameters& catenary)
{
  return SteadyArms().enabled(scene, catenary) ? catenary.steady_arm_positions()
                                               : std::vector<double>{};
}

void SteadyArms::add_terms(SceneAssembly& a) const
{
  const CatenaryParameters& c = a.catenary();
  const std::vector<double> x = c.steady_arm_positions();
  for (unsigned int k = 0; k < x.size(); ++k)
  {
    a.add_point_spring(Wire::contact_wire, x[k], c.steady_arm_stiffness);
    if (k < c.steady_arm_preloads.size())
      a.add_point_force(Wire::contact_wire, x[k], c.steady_arm_preloads[k]);
    if (a.scene.gravity)
      a.add_point_force(Wire::contact_wire, x[k], -c.steady_arm_mass * c.gravity);
    if (c.point_mass_inertia)
      a.add_point_mass(Wire::contact_wire, x[k], c.steady_arm_mass);
  }
}

std::string SteadyArms::describe(const SceneAssembly& a) const
{
  const CatenaryParameters& c = a.catenary();
  return std::to_string(c.steady_arm_positions().size()) +
         " steady arms: k = " + number_to_string(c.steady_arm_stiffness) +
         " N/m, m = " + number_to_string(c.steady_arm_mass) + " kg, preloaded";
}
} // namespace pantocat
