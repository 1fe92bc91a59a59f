#include <pantocat/base/number_format.h>
#include <pantocat/scene/gravity.h>

namespace pantocat
{
std::string Gravity::name() const
{
  return "gravity";
}

bool Gravity::enabled(const SceneParameters& scene) const
{
  return scene.gravity && (scene.carrier == WireModel::elastic ||
                           scene.contact_wire == WireModel::elastic);
}

void Gravity::add_terms(SceneAssembly& a) const
{
  WireTerms t;
  for (const Wire wire : {Wire::carrier, Wire::contact_wire})
  {
    BlockOperator* body = a.body(wire == Wire::carrier ? "carrier" : "contact wire");
    if (body == nullptr)
      continue;
    const WireParameters& p =
        wire == Wire::carrier ? a.catenary.carrier : a.catenary.contact_wire;
    t.weight = p.mass_per_length * a.catenary.gravity;
    a.space.add_terms(wire, t, *body);
  }
}

std::string Gravity::describe(const SceneAssembly& a) const
{
  return "gravity: weight of the elastic wires, g = " +
         number_to_string(a.catenary.gravity) + " m/s^2";
}
} // namespace pantocat
