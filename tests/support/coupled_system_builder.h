#pragma once

#include <pantocat/coupling/contact_constraint.h>
#include <pantocat/pantograph/pantograph_parameters.h>
#include <pantocat/space/catenary_discretisation.h>
#include <pantocat/system/semi_discrete_system.h>

namespace pantocat
{
/// The semi-discrete pantograph-catenary system (35) and its catenary part.
struct CoupledSystem
{
  /// Carrier and contact wire with droppers only (same numbering): the initial static
  /// problem.
  SemiDiscreteSystem catenary_only;
  /// Blocks carrier, contact wire, pantograph; constraints: droppers, then the contact.
  SemiDiscreteSystem coupled;
  const ContactConstraint* contact = nullptr; ///< owned by coupled
  unsigned int contact_index = 0;
};

/**
 * The paper's scene (build_scene() with the default SceneParameters): the
 * catenary (29)-(31), the pantograph block (10) and the
 * contact constraint (32): the coupling layer knows the pantograph only
 * through its operators and b, B.
 */
CoupledSystem build_coupled_system(const CatenaryDiscretisation& discretisation,
                                   const TwoMassPantographParameters& pantograph,
                                   const ContactPointMotion& motion,
                                   Constraint::Kind dropper_kind,
                                   Constraint::Kind contact_kind);
} // namespace pantocat
