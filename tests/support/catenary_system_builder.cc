#include "catenary_system_builder.h"
#include <pantocat/scene/scene_builder.h>

namespace pantocat
{
SemiDiscreteSystem build_catenary_system(const CatenaryDiscretisation& d,
                                         const Constraint::Kind dropper_kind)
{
  SceneParameters scene;
  scene.pantographs[0].model = "absent";
  scene.droppers = dropper_kind == Constraint::Kind::bilateral ? DropperModel::bilateral
                                                               : DropperModel::unilateral;
  return std::move(build_scene(scene, d.catenary_parameters(), d).system);
}

} // namespace pantocat
