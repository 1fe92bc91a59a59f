#include <pantocat/scene/clamp_and_dropper_masses.h>

namespace pantocat
{
std::string ClampAndDropperMasses::name() const
{
  return "clamp and dropper masses";
}

bool ClampAndDropperMasses::enabled(const SceneParameters& scene,
                                    const CatenaryParameters&) const
{
  return scene.clamp_and_dropper_masses && scene.gravity && scene.has_droppers();
}

void ClampAndDropperMasses::add_terms(SceneAssembly& a) const
{
  const CatenaryParameters& p = a.catenary();
  for (unsigned int j = 0; j < p.n_droppers(); ++j)
  {
    // The upper clamp on the carrier, or on the stitch wire the dropper hangs from.
    a.add_at_dropper_top(j, -p.clamp_load(j, true),
                         p.point_mass_inertia ? p.point_mass(j, true) : 0.);
    a.add_point_force(Wire::contact_wire, p.dropper_positions[j],
                      -p.clamp_load(j, false));
    if (p.point_mass_inertia)
      a.add_point_mass(Wire::contact_wire, p.dropper_positions[j],
                       p.point_mass(j, false));
  }
}

std::string ClampAndDropperMasses::describe(const SceneAssembly& a) const
{
  return "clamp and dropper masses: point " +
         std::string(a.catenary().point_mass_inertia ? "masses (inertia and load)"
                                                     : "loads, Eq. (4),") +
         " at " + std::to_string(a.catenary().n_droppers()) + " droppers";
}

void add_dropper_weight_change(const SceneParameters& scene,
                               const CatenaryParameters& catenary,
                               const CatenaryDiscretisation& space,
                               const SemiDiscreteSystem& system,
                               const std::vector<double>& length_changes,
                               dealii::Vector<double>& load)
{
  if (!ClampAndDropperMasses().enabled(scene, catenary))
    return;
  for (unsigned int j = 0; j < catenary.n_droppers(); ++j)
  {
    // clamp_load(j, .) less its clamp part: half the dropper's weight per wire.
    const double weight =
        catenary.half_dropper_mass(length_changes[j]) * catenary.gravity;
    dropper_upper_row(space, system, j).add_transpose_to(load, -weight);
    wire_point_row(space, system, Wire::contact_wire, catenary.dropper_positions[j])
        .add_transpose_to(load, -weight);
  }
}
} // namespace pantocat
