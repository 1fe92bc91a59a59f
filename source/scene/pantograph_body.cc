#include <pantocat/scene/pantograph_body.h>

namespace pantocat
{
std::string PantographBody::name() const
{
  return "pantograph";
}

bool PantographBody::enabled(const SceneParameters& scene,
                             const CatenaryParameters&) const
{
  return scene.has_pantograph_body();
}

void PantographBody::add_bodies(SceneAssembly& a) const
{
  for (const ScenePantograph& p : a.pantographs)
    if (p.model)
    {
      BlockOperator op;
      p.model->assemble(op);
      op.name = p.block;
      a.bodies.push_back(std::move(op));
    }
}

std::string PantographBody::describe(const SceneAssembly& a) const
{
  std::string line;
  for (const ScenePantograph& p : a.pantographs)
    if (p.model)
      line += (line.empty() ? "" : "; ") + p.block + ": " + p.model->name() + " model, " +
              std::to_string(p.model->n_dofs()) + " unknowns";
  return line;
}
} // namespace pantocat
