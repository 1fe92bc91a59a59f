#include <pantocat/scene/pantograph_body.h>

namespace pantocat
{
std::string PantographBody::name() const
{
  return "pantograph";
}

bool PantographBody::enabled(const SceneParameters& scene) const
{
  return scene.has_pantograph_body();
}

void PantographBody::add_bodies(SceneAssembly& a) const
{
  BlockOperator op;
  a.pantograph->assemble(op);
  a.bodies.push_back(std::move(op));
}

std::string PantographBody::describe(const SceneAssembly& a) const
{
  return "pantograph: " + a.pantograph->name() + " model, " +
         std::to_string(a.pantograph->n_dofs()) + " unknowns";
}
} // namespace pantocat
