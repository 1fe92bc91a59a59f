#pragma once

#include <pantocat/analysis/static_equilibrium.h>
#include <pantocat/catenary/catenary_parameters.h>
#include <pantocat/scene/scene_parameters.h>
#include <pantocat/space/catenary_discretisation.h>

#include <vector>

namespace pantocat
{
/// What the static design of a section gives (doc/catenaries.md).
struct CatenaryDesignResult
{
  CatenaryParameters catenary; ///< with the designed lengths and the support preloads
  std::vector<double> dropper_forces; ///< static tension of each dropper [N]
  unsigned int iterations = 0;        ///< fixed-point iterations on the dropper weights
  /// The droppers (0-based) released at zero force: their targets needed a
  /// push (CatenaryParameters::release_unreachable_targets).
  std::vector<unsigned int> released;
};

/**
 * The static design (form-finding) of a tension section, on the grid of
 * @p space, for the catenary alone (no pantograph):
 *
 *  - Design = designed: the dropper lengths l_j such that, under gravity, the
 *    clamp masses and the dropper weights, with every dropper taut and the
 *    supports in place, the static contact wire passes through the target
 *    heights z_j = CatenaryParameters::dropper_target_heights() at the droppers
 *    (Target heights, or the pre-sag parabola) and through 0 at the steady
 *    arms, and the carrier through l_c at the supports. Step 1 solves the
 *    contact wire with these heights as bilateral constraints: their forces
 *    are the dropper tensions F_j. Step 2 loads the carrier with -F_j at the
 *    droppers (a dropper that hangs from a stitch wire loads the stitch wire,
 *    whose clamps pass the load on to the carrier: its shape follows). Then
 *    l_j = w_c(x_j) - z_j, w_c the height of the wire the dropper hangs from
 *    (less F_j / k_d for an elastic dropper). The dropper weights depend on l_j: repeated
 * until l_j changes by less than 1e-10 m (or stops shrinking below 1e-8 m, at the static
 *    solves' round-off). The held catenary is assembled and K factorised
 *    once; each iteration changes only the load by the dropper weights
 *    (add_dropper_weight_change()).
 *  - Springs at the supports (steady arms, carrier springs): their preloads
 *    are the reactions of the supports held fixed in that static state, so
 *    that the sprung catenary is at rest in exactly the same state.
 *
 * The static solves share one StaticEquilibriumSolver: the dense Schur
 * complement for few constraints, the saddle-point system (time and memory
 * near-linear in the length of the section) for many, or for every section
 * with @p column_budget = 0 (see StaticEquilibriumSolver; the results agree
 * to round-off).
 *
 * Throws InputError, naming Pre-sag or Target heights, when the targets ask
 * for a dropper of length <= 0, or for one that would have to push unless
 * the section releases such droppers (Unreachable targets = release): each
 * is then left without its hold, at zero force, the wire where its
 * neighbours put it, and the iteration starts again.
 */
CatenaryDesignResult
design_catenary(const SceneParameters& scene, const CatenaryParameters& catenary,
                const CatenaryDiscretisation& space,
                double column_budget = StaticEquilibriumSolver::default_column_budget);

/// True if @p catenary needs design_catenary(): designed lengths or preloaded springs.
bool needs_design(const SceneParameters& scene, const CatenaryParameters& catenary);
} // namespace pantocat
