#pragma once

#include <pantocat/analysis/static_equilibrium.h>
#include <pantocat/pantograph/pantograph_model.h>
#include <pantocat/scene/scene_parameters.h>
#include <pantocat/space/catenary_discretisation.h>
#include <pantocat/system/semi_discrete_system.h>
#include <pantocat/time/dynamic_state.h>

#include <string>
#include <vector>

namespace pantocat
{
/// A pantograph in contact at t = 0: its model, its contact constraint and block.
struct InitialContact
{
  const PantographModel* model = nullptr;
  unsigned int constraint = 0; ///< index of its contact in the coupled system
  std::string block;           ///< name of its block of unknowns
  double force = 0.;           ///< lambda_p(0) [N]
  double offset = 0.;          ///< w_p1(0) - w_p2(0) [m], (13) and Sec. 6
};

/**
 * Step 1 of the consistent initial state: the catenary at rest (v = a = 0)
 * solves the elliptic problem with its loads at t = 0 (gravity, clamps,
 * moving forces at their initial positions), its droppers and every contact
 * load lambda_p(0) F_w(0)^T (Fig. 5), in the numbering of @p catenary_only.
 */
StaticEquilibrium static_catenary(const SemiDiscreteSystem& catenary_only,
                                  const SemiDiscreteSystem& coupled,
                                  const std::vector<InitialContact>& contacts);

/**
 * The paper's start (Run/Start = paper), the consistent initial state of
 * Sec. 2.2 for the system of a scene:
 *  1. static_catenary();
 *  2. each head's position, velocity and acceleration follow from its contact
 *     constraint and the hidden constraints (Sec. 4.1) with v_w = a_w = 0:
 *     B q_MBS = F_w q_w, B v_MBS = G_t q, B a_MBS = G_tt q;
 *  3. each pantograph model completes q_MBS, v_MBS with (13) (plus the offset)
 *     and its equations of motion with lambda_p(0);
 *  4. a = M^-1 (f(0) - K q - D v + G^T lambda) for the whole system.
 * On position, velocity and acceleration level the state is consistent, so
 * the first step returns lambda_p = lambda_p(0).
 *
 * @p catenary_only is the system without the pantographs' effects (same
 * numbering of the catenary unknowns and of the droppers), @p coupled the
 * full one.
 */
DynamicState consistent_initial_state(const SemiDiscreteSystem& catenary_only,
                                      const SemiDiscreteSystem& coupled,
                                      const std::vector<InitialContact>& contacts);

/**
 * The start Run/Start = static equilibrium, as benchmark codes start: the
 * catenary and every pantograph at rest in the static equilibrium of the
 * whole system under its loads at t = 0 (gravity, clamps, each pantograph's
 * static and aerodynamic force), the contacts and droppers included, so each
 * contact starts with the force its pantograph exerts at that height (its
 * static force when its springs to the ground carry nothing). Each pantograph
 * then moves as one rigid body with the vertical velocity of the wire under
 * its moving contact point (B v_MBS = G_t q + z_t, the contact's velocity
 * level); no spring or damper inside it is loaded by the start.
 * Accelerations follow from the equations of motion. @p contacts name the
 * pantographs in contact (their model, block and contact; force and offset
 * are not used).
 */
DynamicState static_initial_state(const SemiDiscreteSystem& coupled,
                                  const std::vector<InitialContact>& contacts);

/**
 * A state that ignores constraints (the scene must have none): at rest,
 * undeformed (InitialShape::rest) or with the contact wire in the shape
 * A sin(k pi x / L) (InitialShape::sine_mode), and a = M^-1 (f(0) - K q).
 */
DynamicState shaped_initial_state(const SemiDiscreteSystem& system,
                                  const CatenaryDiscretisation& space,
                                  const SceneParameters& scene);
} // namespace pantocat
