#pragma once

#include <pantocat/system/semi_discrete_system.h>

#include <deal.II/lac/vector.h>

#include <vector>

namespace pantocat
{
/// The solution of the elliptic problem of Sec. 2.2: q and the constraint forces.
struct StaticEquilibrium
{
  dealii::Vector<double> q;
  /// lambda_i >= 0 of each constraint (0 when inactive; a compliant one's spring force)
  std::vector<double> multipliers;
  std::vector<double> gaps; ///< g_i(t, q)
  std::vector<bool> active; ///< the active set of the solution
  unsigned int active_set_iterations = 0;
};

/**
 * Solves K q = f + f_extra + G^T lambda with the constraints of @p system at
 * time @p t: bilateral ones as g = 0, unilateral ones with the complementarity
 * conditions (5), (6) (an active-set iteration: drop lambda < 0, add g < 0).
 *
 * Compliant constraints (Constraint::is_compliant) are springs: an engaged
 * one has lambda = -k g (the row g + lambda/k = 0 of the Schur complement,
 * G K^-1 G^T + diag(1/k)); a unilateral one is engaged (in `active`) iff its
 * force is positive, iterated like the active set (a taut elastic dropper
 * pulls, a slack one does not).
 *
 * K is factorised once by a sparse direct solver (UMFPACK); the few
 * multipliers follow from the small dense Schur complement G K^{-1} G^T.
 * Throws SimulationError if K or the Schur complement is singular or the
 * active set cycles.
 */
StaticEquilibrium solve_static_equilibrium(const SemiDiscreteSystem& system,
                                           const dealii::Vector<double>& extra_load,
                                           double t = 0.);
} // namespace pantocat
