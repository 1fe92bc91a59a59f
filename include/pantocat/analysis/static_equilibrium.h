#pragma once

#include <pantocat/lac/sparse_direct_solver.h>
#include <pantocat/system/semi_discrete_system.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <vector>

namespace pantocat
{
class InterleavedColumns;

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
 * The static problem K q = f + f_extra + G^T lambda of a system with the
 * constraints of @p system at time @p t, prepared once for many loads:
 * bilateral constraints as g = 0, unilateral ones with the complementarity
 * conditions (5), (6) (an active-set iteration: drop lambda < 0, add g < 0).
 *
 * Compliant constraints (Constraint::is_compliant) are springs: an engaged
 * one has lambda = -k g (the row g + lambda/k = 0 of the Schur complement,
 * G K^-1 G^T + diag(1/k)); a unilateral one is engaged (in `active`) iff its
 * force is positive, iterated like the active set (a taut elastic dropper
 * pulls, a slack one does not).
 *
 * Two ways to the same solution (to round-off):
 *
 *  - Few constraints (n m within the column budget and m <= max_dense_constraints,
 *    every shipped case): the constructor factorises K once by a sparse direct
 *    solver (the banded Cholesky of SparseDirectSolver; K is symmetric positive
 *    definite and banded within each body) and forms X = K^-1 G^T and the Schur
 *    complement S = G K^-1 G^T of every constraint (back-substitutions of four
 *    constraints side by side); a solve() is then one back-substitution for its
 *    load plus, per active-set iteration, a small dense solve with the rows and
 *    columns of S of the active constraints. K, G and z do not depend on the
 *    load, so any number of loads (the static elasticity: one per load point and
 *    force; the dropper design's iterations) share this work, and the inverse of
 *    the last active set's S is kept for the next solve with the same set.
 *  - Many constraints (a long section: X costs O(n m), S O(m^2) memory and its
 *    inverse O(m^3) time): the saddle-point system
 *
 *      [ K    G_a^T ] [     q     ]   [ f + f_extra ]
 *      [ G_a  -C_a  ] [ -lambda_a ] = [    -z_a     ]
 *
 *    of the active constraints a (C_a their compliances 1/k, 0 for rigid ones)
 *    is factorised by UMFPACK, whose fill-reducing ordering keeps the factor of
 *    this banded-plus-point-rows matrix O(n + m): time and memory near-linear in
 *    the length of the section. The factor of the last active set is kept for
 *    the next solve with the same set.
 *    This is also the way when K alone is singular
 *    (SemiDiscreteSystem::stiffness_is_definite = false: stitch wires, held
 *    by their clamps to the carrier), whatever the number of constraints.
 *
 * Keeps a reference to @p system, which must outlive it. Not for solve()
 * calls from several threads at once (the kept inverse or factor).
 */
class StaticEquilibriumSolver
{
public:
  /**
   * The dense Schur complement (the first way of the class comment) is taken
   * while n m stays within this many numbers (8 MB of columns K^-1 G^T) ...
   */
  static constexpr double default_column_budget = 1 << 20;
  /// ... and m is at most this (its inverse costs m^3 / 3 operations).
  static constexpr unsigned int max_dense_constraints = 512;

  /**
   * Throws SimulationError if K is singular. @p column_budget: see
   * default_column_budget (0: always the saddle-point system; the results
   * agree to round-off).
   */
  explicit StaticEquilibriumSolver(const SemiDiscreteSystem& system, double t = 0.,
                                   double column_budget = default_column_budget);

  /**
   * The equilibrium under f + @p extra_load, the active set iterated from
   * all constraints active. Throws SimulationError if the active constraints
   * are linearly dependent or the active set cycles.
   */
  StaticEquilibrium solve(const dealii::Vector<double>& extra_load) const;

  /**
   * As solve(), with the active-set iteration started from @p initial_active
   * (one flag per constraint), e.g. the active set of a neighbouring load:
   * the solution is the same, usually after fewer iterations.
   */
  StaticEquilibrium solve(const dealii::Vector<double>& extra_load,
                          const std::vector<bool>& initial_active) const;

  unsigned int n_constraints() const { return states.size(); }
  /// True if solve() factorises the saddle-point system (many constraints).
  bool uses_saddle_point_system() const { return saddle_point; }

private:
  /// Solves for the multipliers of the constraints in @p active; fills q and lambda.
  void solve_with_active_set(const std::vector<bool>& active,
                             const dealii::Vector<double>& q_free,
                             StaticEquilibrium& out) const;
  /// The constraint to switch next (Sec. 5.3), or -1 if @p s is the solution.
  int constraint_to_switch(const StaticEquilibrium& s) const;

  const SemiDiscreteSystem& system;
  SparseDirectSolver K_inverse;
  std::vector<ConstraintState> states; ///< G and z of every constraint at t
  /**
   * Column c of @p batch <- K^-1 G_i^T for the constraints i =
   * @p constraints[first + c], c < 4 (the others zero); returns how many.
   */
  unsigned int columns(const std::vector<unsigned int>& constraints, unsigned int first,
                       InterleavedColumns& batch) const;
  /// The saddle-point way: solves for q and the multipliers of @p active under
  /// the load @p load (f + f_extra); fills q and lambda.
  void solve_saddle_point(const std::vector<bool>& active,
                          const dealii::Vector<double>& load,
                          StaticEquilibrium& out) const;
  /// Factorises the saddle-point matrix of the constraints @p act (the flags
  /// @p active) unless it is the kept one. Throws SimulationError if singular.
  void factorize_saddle_point(const std::vector<bool>& active,
                              const std::vector<unsigned int>& act) const;
  /**
   * (G K^-1 G^T + C)^-1 of the constraints @p act (the flags @p active), C
   * the engaged compliances; inverted when the active set differs from the
   * last one's, else kept: solves under several loads with one active set
   * (the dropper design's iterations) invert it once. Throws SimulationError
   * if it is singular.
   */
  const dealii::FullMatrix<double>&
  S_inverse_of(const std::vector<bool>& active,
               const std::vector<unsigned int>& act) const;

  bool saddle_point = false;             ///< the second way of the class comment
  std::vector<dealii::Vector<double>> X; ///< K^-1 G_i^T of every constraint i, or empty
  dealii::FullMatrix<double> schur;      ///< G K^-1 G^T of all constraints, or empty
  mutable std::vector<bool> inverse_active;     ///< the set S_inverse belongs to
  mutable dealii::FullMatrix<double> S_inverse; ///< see S_inverse_of()
  mutable std::vector<bool> factor_active;      ///< the set `factor` belongs to
  mutable SparseDirectSolver factor;            ///< see factorize_saddle_point()
};

/**
 * The equilibrium of @p system under f + @p extra_load at time @p t, for a
 * single load: StaticEquilibriumSolver(system, t).solve(extra_load). Throws
 * SimulationError if K or the Schur complement is singular or the active set
 * cycles.
 */
StaticEquilibrium solve_static_equilibrium(const SemiDiscreteSystem& system,
                                           const dealii::Vector<double>& extra_load,
                                           double t = 0.);
} // namespace pantocat
