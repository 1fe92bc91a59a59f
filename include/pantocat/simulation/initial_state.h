#pragma once

#include <pantocat/pantograph/pantograph_model.h>
#include <pantocat/scene/scene_parameters.h>
#include <pantocat/space/catenary_discretisation.h>
#include <pantocat/system/semi_discrete_system.h>
#include <pantocat/time/dynamic_state.h>

namespace pantocat
{
/**
 * The consistent initial state of Sec. 2.2 for the system of a scene:
 *  1. the catenary at rest (v = a = 0) solves the elliptic problem with its
 *     loads (gravity, clamps, a moving force at x_p(0)), droppers and the
 *     contact load lambda_p(0) F_w(0)^T;
 *  2. the head position, velocity and acceleration follow from the contact
 *     constraint and its hidden constraints (Sec. 4.1) with v_w = a_w = 0:
 *     B q_MBS = F_w q_w, B v_MBS = G_t q, B a_MBS = G_tt q;
 *  3. the pantograph model completes q_MBS, v_MBS with (13) (plus the offset)
 *     and its equations of motion with lambda_p(0);
 *  4. a = M^-1 (f(0) - K q - D v + G^T lambda) for the whole system.
 * On position, velocity and acceleration level the state is consistent, so
 * the first step returns lambda_p = lambda_p(0).
 *
 * @p catenary_only is the system without the pantograph's effects (same
 * numbering of the catenary unknowns and of the droppers), @p coupled the
 * full one; @p pantograph and @p contact_index (invalid_unsigned_int: none)
 * are the scene's lumped-mass pantograph and its contact, if it has them.
 */
DynamicState consistent_initial_state(const SemiDiscreteSystem& catenary_only,
                                      const SemiDiscreteSystem& coupled,
                                      const PantographModel* pantograph,
                                      unsigned int contact_index,
                                      double initial_contact_force, double offset);

/**
 * A state that ignores constraints (the scene must have none): at rest,
 * undeformed (InitialShape::rest) or with the contact wire in the shape
 * A sin(k pi x / L) (InitialShape::sine_mode), and a = M^-1 (f(0) - K q).
 */
DynamicState shaped_initial_state(const SemiDiscreteSystem& system,
                                  const CatenaryDiscretisation& space,
                                  const SceneParameters& scene);
} // namespace pantocat
