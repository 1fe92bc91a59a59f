#include <pantocat/base/number_format.h>
#include <pantocat/scene/rayleigh_damping.h>

namespace pantocat
{
std::string RayleighDamping::name() const
{
  return "Rayleigh damping";
}

bool RayleighDamping::enabled(const SceneParameters& scene,
                              const CatenaryParameters& catenary) const
{
  return scene.damping && catenary.damping == CatenaryDamping::rayleigh &&
         (scene.carrier == WireModel::elastic ||
          scene.contact_wire == WireModel::elastic);
}

void RayleighDamping::add_terms(SceneAssembly& a) const
{
  for (BlockOperator* b :
       {a.wire_body(Wire::carrier), a.wire_body(Wire::contact_wire), a.stitch_body()})
    if (b != nullptr)
    {
      b->damping.add(a.catenary().rayleigh_alpha, b->mass);
      b->damping.add(a.catenary().rayleigh_beta, b->stiffness);
    }
}

std::string RayleighDamping::describe(const SceneAssembly& a) const
{
  return "damping: Rayleigh C = " + number_to_string(a.catenary().rayleigh_alpha) +
         " M + " + number_to_string(a.catenary().rayleigh_beta) + " K (wires" +
         std::string(a.catenary().stitch_wires.empty() ? "" : " and stitch wires") +
         ", without droppers)";
}
} // namespace pantocat
