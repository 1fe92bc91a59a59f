#include <pantocat/base/number_format.h>
#include <pantocat/scene/contact_wire_bending.h>

namespace pantocat
{
std::string ContactWireBending::name() const
{
  return "bending";
}

bool ContactWireBending::enabled(const SceneParameters& scene) const
{
  return scene.contact_wire == WireModel::elastic && scene.contact_wire_bending;
}

void ContactWireBending::add_terms(SceneAssembly& a) const
{
  WireTerms t;
  t.bending = a.catenary.contact_wire.bending_stiffness;
  a.space.add_terms(Wire::contact_wire, t, *a.body("contact wire"));
}

std::string ContactWireBending::describe(const SceneAssembly& a) const
{
  return "bending: contact wire E I = " +
         number_to_string(a.catenary.contact_wire.bending_stiffness) + " N m^2";
}
} // namespace pantocat
