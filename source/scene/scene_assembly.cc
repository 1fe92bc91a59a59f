#include <pantocat/scene/scene_assembly.h>

namespace pantocat
{
BlockOperator* SceneAssembly::body(const std::string& name)
{
  for (BlockOperator& b : bodies)
    if (b.name == name)
      return &b;
  return nullptr;
}

SparseRow SceneAssembly::wire_row(const Wire wire, const double x) const
{
  const std::string name = wire == Wire::carrier ? "carrier" : "contact wire";
  if (!system.has_block(name))
    return {};
  SparseRow row = space.point_row(wire, x);
  row.shift(system.block(name).first);
  return row;
}
} // namespace pantocat
