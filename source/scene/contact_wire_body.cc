#include <pantocat/scene/contact_wire_body.h>

namespace pantocat
{
std::string ContactWireBody::name() const
{
  return "contact wire";
}

bool ContactWireBody::enabled(const SceneParameters& scene,
                              const CatenaryParameters&) const
{
  return scene.contact_wire == WireModel::elastic;
}

void ContactWireBody::add_bodies(SceneAssembly& a) const
{
  a.add_wire_body(Wire::contact_wire, a.scene.contact_wire_bending);
}

std::string ContactWireBody::describe(const SceneAssembly& a) const
{
  return "contact wire: elastic, " +
         std::to_string(a.space().n_dofs(Wire::contact_wire)) + " unknowns";
}
} // namespace pantocat
