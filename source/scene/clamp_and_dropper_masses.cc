#include <pantocat/scene/clamp_and_dropper_masses.h>

namespace pantocat
{
std::string ClampAndDropperMasses::name() const
{
  return "clamp and dropper masses";
}

bool ClampAndDropperMasses::enabled(const SceneParameters& scene) const
{
  return scene.clamp_and_dropper_masses && scene.gravity && scene.has_droppers();
}

void ClampAndDropperMasses::add_terms(SceneAssembly& a) const
{
  const CatenaryParameters& p = a.catenary;
  for (unsigned int j = 0; j < p.n_droppers(); ++j)
    for (const Wire wire : {Wire::carrier, Wire::contact_wire})
      if (BlockOperator* body = a.body(block_name(wire)))
        a.space.point_row(wire, p.dropper_positions[j])
            .add_transpose_to(body->load, -p.clamp_load(j));
}

std::string ClampAndDropperMasses::describe(const SceneAssembly& a) const
{
  return "clamp and dropper masses: point loads at " +
         std::to_string(a.catenary.n_droppers()) + " droppers, Eq. (4)";
}
} // namespace pantocat
