#include <pantocat/scene/carrier_body.h>

namespace pantocat
{
std::string CarrierBody::name() const
{
  return "carrier";
}

bool CarrierBody::enabled(const SceneParameters& scene, const CatenaryParameters&) const
{
  return scene.carrier == WireModel::elastic;
}

void CarrierBody::add_bodies(SceneAssembly& a) const
{
  a.add_wire_body(Wire::carrier, a.scene.carrier_bending);
}

std::string CarrierBody::describe(const SceneAssembly& a) const
{
  return std::string("carrier: elastic ") +
         (a.scene.carrier_bending ? "beam, " : "string, ") +
         std::to_string(a.space().n_dofs(Wire::carrier)) + " unknowns";
}
} // namespace pantocat
