#include <pantocat/base/number_format.h>
#include <pantocat/scene/viscous_damping.h>

namespace pantocat
{
std::string ViscousDamping::name() const
{
  return "damping";
}

bool ViscousDamping::enabled(const SceneParameters& scene,
                             const CatenaryParameters& catenary) const
{
  return scene.damping && catenary.damping == CatenaryDamping::viscous &&
         (scene.carrier == WireModel::elastic ||
          scene.contact_wire == WireModel::elastic);
}

void ViscousDamping::add_terms(SceneAssembly& a) const
{
  for (const Wire wire : {Wire::carrier, Wire::contact_wire})
  {
    WireTerms t;
    t.damping = a.wire_parameters(wire).damping;
    a.add_wire_terms(wire, t);
  }
}

std::string ViscousDamping::describe(const SceneAssembly& a) const
{
  return "damping: beta = " + number_to_string(a.catenary().carrier.damping) + ", " +
         number_to_string(a.catenary().contact_wire.damping) +
         " N s/m^2 (carrier, contact wire)";
}
} // namespace pantocat
