#include <pantocat/coupling/coupled_system_builder.h>
#include <pantocat/scene/scene_builder.h>

namespace pantocat
{
CoupledSystem build_coupled_system(const CatenaryDiscretisation& discretisation,
                                   const PantographModel& pantograph,
                                   const ContactPointMotion& motion,
                                   const Constraint::Kind dropper_kind,
                                   const Constraint::Kind contact_kind)
{
  SceneParameters scene;
  scene.droppers = dropper_kind == Constraint::Kind::bilateral ? DropperModel::bilateral
                                                               : DropperModel::unilateral;
  scene.contact = contact_kind;
  BuiltScene built = build_scene(scene, discretisation.catenary_parameters(),
                                 discretisation, &pantograph, motion);
  CoupledSystem s;
  s.catenary_only = std::move(built.catenary_only);
  s.coupled = std::move(built.system);
  s.contact_index = built.contact_index;
  s.contact = dynamic_cast<const ContactConstraint*>(
      s.coupled.constraints[s.contact_index].get());
  return s;
}
} // namespace pantocat
