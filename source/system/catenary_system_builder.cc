#include <pantocat/scene/scene_builder.h>
#include <pantocat/system/catenary_system_builder.h>

namespace pantocat
{
SemiDiscreteSystem build_catenary_system(const CatenaryDiscretisation& d,
                                         const Constraint::Kind dropper_kind)
{
  SceneParameters scene;
  scene.pantograph = PantographType::absent;
  scene.droppers = dropper_kind == Constraint::Kind::bilateral ? DropperModel::bilateral
                                                               : DropperModel::unilateral;
  return std::move(build_scene(scene, d.catenary_parameters(), d, nullptr, {}).system);
}

SparseRow wire_point_row(const CatenaryDiscretisation& d,
                         const SemiDiscreteSystem& system, const Wire wire,
                         const double x)
{
  if (!system.has_block(block_name(wire)))
    return {};
  SparseRow row = d.point_row(wire, x);
  row.shift(system.block(block_name(wire)).first);
  return row;
}
} // namespace pantocat
