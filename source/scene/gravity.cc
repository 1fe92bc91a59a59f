#include <pantocat/base/number_format.h>
#include <pantocat/scene/gravity.h>

namespace pantocat
{
std::string Gravity::name() const
{
  return "gravity";
}

bool Gravity::enabled(const SceneParameters& scene, const CatenaryParameters&) const
{
  return scene.gravity && (scene.carrier == WireModel::elastic ||
                           scene.contact_wire == WireModel::elastic);
}

void Gravity::add_terms(SceneAssembly& a) const
{
  for (const Wire wire : {Wire::carrier, Wire::contact_wire})
  {
    WireTerms t;
    t.weight = a.wire_parameters(wire).mass_per_length * a.catenary().gravity;
    a.add_wire_terms(wire, t);
  }
}

std::string Gravity::describe(const SceneAssembly& a) const
{
  return "gravity: weight of the elastic wires, g = " +
         number_to_string(a.catenary().gravity) + " m/s^2";
}
} // namespace pantocat
