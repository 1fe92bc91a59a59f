#include "coupled_system_builder.h"
#include <pantocat/coupling/contact_constraint.h>
#include <pantocat/scene/scene_builder.h>

namespace pantocat
{
CoupledSystem build_coupled_system(const CatenaryDiscretisation& discretisation,
                                   const TwoMassPantographParameters& pantograph,
                                   const ContactPointMotion& motion,
                                   const Constraint::Kind dropper_kind,
                                   const Constraint::Kind contact_kind)
{
  SceneParameters scene;
  scene.droppers = dropper_kind == Constraint::Kind::bilateral ? DropperModel::bilateral
                                                               : DropperModel::unilateral;
  PantographCase& p = scene.pantographs[0];
  p.contact = contact_kind;
  p.parameters.two_mass = pantograph;
  p.parameters.initial_position = motion.initial_position;
  p.parameters.speed = motion.speed;
  BuiltScene built =
      build_scene(scene, discretisation.catenary_parameters(), discretisation);
  CoupledSystem s;
  s.catenary_only = std::move(built.catenary_only);
  s.coupled = std::move(built.system);
  s.contact_index = built.pantographs[0].contact_index;
  s.contact = dynamic_cast<const ContactConstraint*>(
      s.coupled.constraints[s.contact_index].get());
  return s;
}
} // namespace pantocat
