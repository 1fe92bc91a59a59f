#pragma once

#include <pantocat/coupling/contact_constraint.h>
#include <pantocat/pantograph/pantograph_model.h>
#include <pantocat/system/semi_discrete_system.h>
#include <pantocat/time/dynamic_state.h>

namespace pantocat
{
/**
 * The consistent initial state of Sec. 2.2 for the coupled system:
 *  1. the catenary at rest (v = a = 0) solves the elliptic problem with
 *     gravity, clamp loads, droppers and the contact load lambda_p(0) F_w(0)^T;
 *  2. the head position, velocity and acceleration follow from the contact
 *     constraint and its hidden constraints (Sec. 4.1) with v_w = a_w = 0:
 *     B q_MBS = F_w q_w, B v_MBS = G_t q, B a_MBS = G_tt q;
 *  3. the pantograph model completes q_MBS, v_MBS with (13) (plus the offset)
 *     and its equations of motion with lambda_p(0);
 *  4. a = M^-1 (f - K q - D v + G^T lambda) for the whole system.
 * On position, velocity and acceleration level the state is consistent, so
 * the first step returns lambda_p = lambda_p(0).
 *
 * @p catenary_only is the system without the pantograph (same numbering of
 * the catenary unknowns), @p coupled the full one whose last constraint is
 * @p contact.
 */
DynamicState consistent_initial_state(const SemiDiscreteSystem& catenary_only,
                                      const SemiDiscreteSystem& coupled,
                                      const PantographModel& pantograph,
                                      const ContactConstraint& contact,
                                      double initial_contact_force, double offset);
} // namespace pantocat
