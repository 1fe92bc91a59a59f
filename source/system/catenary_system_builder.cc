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
} // namespace pantocat
