#include <pantocat/base/number_format.h>
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

std::string SceneAssembly::load_shape() const
{
  if (space.discretisation_parameters().load_shape == LoadShape::point)
    return "point load (15)/(16)";
  return "smoothed delta_eps (25), eps = " +
         number_to_string(space.smoothed_delta().epsilon()) + " m";
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
