#pragma once

#include <pantocat/lac/interleaved_columns.h>
#include <pantocat/lac/sparse_direct_solver.h>
#include <pantocat/system/constraint.h>
#include <pantocat/constrained_fast/damping_over_mass.h>
#include <pantocat/constrained_fast/fixed_constraint_schur.h>
#include <pantocat/constrained_fast/mass_inverse.h>
#include <pantocat/constrained_fast/truncated_columns.h>

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <vector>

namespace pantocat
{
/**
 * The block of the constraints with constant rows (droppers, supports) in
 * the multiplier system of a BDF step on the GGL formulation (38)
 * (Bdf2Integrator), solved in O(m) per step.
 *
 * With S = K + c D + c^2 M, P = G S^-1 G^T, Q = G S^-1 (c G^T + D M^-1 G^T)
 * and N = G M^-1 G^T over these constraints (G_t = G_tt = 0), the levels
 * g, dg/dt, d2g/dt2 of the step's solution depend on the multipliers
 * (lambda, eta, mu) through
 *
 *   level 0: P (lambda + eta) + Q mu,   level 1: c level 0 - N mu,
 *   level 2: c level 1 - N eta.
 *
 * So the rows "level 1 - c level 0" and "level 2 - c level 1" hold only
 * -N mu and -N eta. For the constraints with force F and the engaged elastic
 * ones E (law lambda/k + g + d dg/dt = 0, d = c_damping/k), the block solves
 *
 *   mu_F = -N_FF^-1 r_1,   eta_F = -N_FF^-1 r_2,
 *   (P + C)_{F+E} lambda = r_0 - P eta - Q mu  (E rows: their law / (1 + d c)),
 *
 * with C = diag(1 / (k (1 + d c))) on E: two symmetric banded Schur
 * complements (FixedConstraintSchur), factorised when the sets change.
 * Touching constraints (g = dg/dt = 0 without force) and the moving
 * contacts are not in the block: the integrator borders it with them.
 *
 * Block vectors have three slots per constraint k, entry 3k + s. Equations:
 * s = 0: level 2 - c level 1 (k in F) or the law (k in E); s = 1: level 0;
 * s = 2: level 1 - c level 0. Unknowns: s = 0: lambda, 1: eta, 2: mu.
 */
class GglFixedBlock
{
public:
  /**
   * Computes P, Q, N and the truncated columns S^-1 G^T, S^-1 (c G^T +
   * D M^-1 G^T), M^-1 G^T for the rows @p G of the constraints @p constraints.
   * @p DM gives D M^-1 G^T as sparse rows where the bodies allow it.
   */
  void initialize(const std::vector<const SparseRow*>& G,
                  const std::vector<const Constraint*>& constraints,
                  const SparseDirectSolver& S, const MassInverse& M,
                  const dealii::SparseMatrix<double>& D, const DampingOverMass& DM,
                  double c, unsigned int n_dofs);

  unsigned int size() const { return m; }

  /**
   * The constraints with force (@p force) and the engaged elastic ones
   * (@p engaged). Of those with force, the settled ones (@p settled, empty:
   * none) take lambda alone: their eta = mu = 0 and their levels 1 and 2 are
   * not equations of the block.
   *
   * Why that is the same step: a constraint with a constant row (G_t = G_tt =
   * 0) that held at the step's history points (G q = z, G v = 0 there) gets
   * G v = c G q - G rho_q = 0 and G a = c G v - G rho_v = 0 from its
   * position level alone, since the BDF formulas' weights sum to c; so
   * eta = mu = 0 solve levels 1 and 2 in exact arithmetic. In floating point
   * they only carried the round-off of the history, amplified by c and c^2
   * (about 1e-8 of lambda at dt = 5e-5 s), which the BDF formulas keep
   * bounded without them (it does not accumulate: each level is formed from
   * the positions anew). Bdf2Integrator calls a constraint settled if it held
   * at every history point of the step and no moving or touching
   * constraint's columns M^-1 G^T reach its row; a settled constraint that N
   * couples to an unsettled one with force keeps eta and mu as well.
   */
  void select(const std::vector<bool>& force, const std::vector<bool>& engaged,
              const std::vector<bool>& settled = {});
  /// True if some constraint with force is not settled (the block has eta, mu).
  bool has_velocity_multipliers() const { return with_eta_mu; }
  /// True if constraint k has eta and mu in the selection (with force, not settled).
  bool has_eta_mu(const unsigned int k) const { return eta_mu_set[k]; }
  /// Number of constraints with force that take lambda alone in the selection.
  unsigned int n_settled() const { return settled_count; }
  /// d = c_damping / k of constraint k (0 if rigid).
  double damping_ratio(unsigned int k) const { return ratio[k]; }

  /// Each x <- A^-1 x (equation slots in, unknown slots out; 0 off the sets).
  void solve(const std::vector<dealii::Vector<double>*>& xs) const;

  /**
   * Finds the subset (local_members()) of the block's constraints whose
   * multipliers a right-hand side with entries on the slots of @p sources
   * alone moves by more than the unit round-off (relative to those of the
   * sources), ascending: the sources in the block, the reach of N among
   * those with eta and mu, the constraints that Q (and, for the engaged
   * ones, N) couples to those, and the reach of P + C from all these
   * (FixedConstraintSchur::reach_from(), 2^-53). Returns false if they are
   * more than max_local_subset: solve() then.
   *
   * A moving contact's border columns (Bc of Bdf2Integrator) have entries on
   * the few fixed rows that its columns reach; droppers 5 m apart couple in P
   * and N by about 1e-15 of their diagonals, so the subset is those rows and
   * one neighbour on each side.
   */
  bool local_subset(const std::vector<unsigned int>& sources);
  /// The subset of the latest local_subset().
  const std::vector<unsigned int>& local_members() const { return local.subset; }
  /**
   * Each x <- A^-1 x for right-hand sides with entries on the slots of the
   * last local_subset()'s constraints R alone, solved on R (P + C, N and Q
   * restricted to R, dense, factorised again only when R changes);
   * the slots off R are not read and keep their zeros. The multipliers
   * differ from solve()'s by the round-off of the dropped couplings (below
   * 2^-53 of the sources' along every path) and of the dense factors.
   */
  void solve_local(const std::vector<dealii::Vector<double>*>& xs);
  /// Most constraints of a local solve (dense factors of this order at most).
  static constexpr unsigned int max_local_subset = 32;

  /**
   * The multipliers' share of a step's vectors: q += S^-1 G^T (lambda + eta) +
   * S^-1 (c G^T + D M^-1 G^T) mu, u1 += M^-1 G^T mu, u2 += M^-1 G^T eta
   * (Bdf2Integrator: v = c q - rho_q - u1, a = c v - rho_v - u2). From the
   * truncated columns, or, when they cost more than the solves (many
   * constraints on a FEM grid), from two solves with M and one with S: the
   * right-hand side of S gathered from the sparse rows G_k and D M^-1 G_k^T
   * (DampingOverMass), or, for bodies without that structure, with D
   * applied to M^-1 G^T mu.
   */
  void add_forces(const std::vector<double>& lambda_plus_eta,
                  const std::vector<double>& eta, const std::vector<double>& mu,
                  dealii::Vector<double>& q, dealii::Vector<double>& u1,
                  dealii::Vector<double>& u2) const;

  /**
   * The sums of add_forces() from the truncated columns, not added (only when
   * !adds_forces_by_solves()): q.first = S^-1 G^T (lambda + eta) on
   * q.first_rows, then q.second = S^-1 (c G^T + D M^-1 G^T) mu on
   * q.second_rows; u.first = M^-1 G^T mu (u1) and u.second = M^-1 G^T eta
   * (u2) on u.first_rows. The caller adds them in that order and zeroes them
   * (Bdf2Integrator::combine_trial(), in its one pass over the unknowns).
   * Without eta and mu (!has_velocity_multipliers()) only q.first is formed
   * (the other rows null).
   */
  struct ForceSums
  {
    TruncatedColumns::Sums q, u;
  };
  ForceSums sum_forces(const std::vector<double>& lambda_plus_eta,
                       const std::vector<double>& eta,
                       const std::vector<double>& mu) const;
  /**
   * True if sum_forces() is offered and pays: the sums reach few stretches of
   * rows, at least 64 unknowns per stretch on average, so that a pass split at
   * their ends costs less than add_forces()' copy, zeroing and additions
   * (bench_constraints: 200 droppers 5 m apart on FEM, one stretch per sum,
   * 6 % faster; 40 on the 100 m FDM grid, 240 stretches, 9 % slower).
   */
  bool sums_in_one_pass() const
  {
    return !solves_are_cheaper && 64 * (X.n_row_ranges() + Y.n_row_ranges()) <=
                                      static_cast<std::size_t>(n_unknowns);
  }

  /// True if add_forces() solves rather than adds the truncated columns.
  bool adds_forces_by_solves() const { return solves_are_cheaper; }
  /// Makes add_forces() solve (@p solves) or add the columns, whatever they
  /// cost (the tests compare both ways).
  void set_forces_by_solves(bool solves);

  /// The time of one multiply-add of the columns' slices (four unknowns) in
  /// entries of a substitution (measured with bench_constraints, see initialize()).
  static constexpr double slice_operation_cost = 1.9;

  /// Columns S^-1 G^T (of lambda and eta) with their partners S^-1 (c G^T +
  /// D M^-1 G^T) (of mu); M^-1 G^T.
  const TruncatedColumns& stiffness_columns() const { return X; }
  const TruncatedColumns& mass_columns() const { return Y; }

private:
  unsigned int m = 0, n_unknowns = 0;
  double c = 0.;
  FixedConstraintSchur P, N; ///< P + C on F + E, N on F
  CompressedRows Q;          ///< Q by rows
  TruncatedColumns X, Y;     ///< X: X^lambda with X^mu as partners
  std::vector<double> ratio;
  std::vector<SparseRow> rows; ///< G of the constraints
  const SparseDirectSolver* S_inverse = nullptr;
  const MassInverse* M_inverse = nullptr;
  const dealii::SparseMatrix<double>* damping = nullptr;
  bool solves_are_cheaper = false; ///< add_forces() by solves
  /// D M^-1 G_k^T of each constraint (empty if a body lacks the structure).
  std::vector<SparseRow> damping_rows;
  /// Workspace of add_forces(): the right-hand sides of S and of M (twice).
  mutable dealii::Vector<double> work, mass_mu, mass_eta, D_y;
  /// Workspace of solve().
  mutable std::vector<dealii::Vector<double>> mu_w, eta_w, rhs_w;
  mutable std::vector<dealii::Vector<double>*> batch_w;
  mutable std::vector<char> mu_zero_w, eta_zero_w;
  mutable std::vector<dealii::Vector<double>> Q_mu_w; ///< Q mu per right-hand side
  mutable std::vector<std::size_t> with_mu_w;
  mutable dealii::Vector<double> P_eta, N_mu;
  std::vector<bool> force_set, engaged_set;
  std::vector<bool> settled_set; ///< select()'s last arguments
  bool selected_once = false;
  std::vector<bool> eta_mu_set; ///< force and not settled
  bool with_eta_mu = false;
  bool any_engaged = false;          ///< some constraint in engaged_set
  std::vector<bool> with_lambda_set; ///< force or engaged (P's selection)
  RowsByColumn Q_by_column;          ///< Q's pattern by column
  /// The constraints with eta and mu; when they are at most max_local_subset,
  /// N restricted to them, dense (solve() takes it instead of N's banded factor).
  std::vector<unsigned int> eta_mu_list, factorised_eta_mu_list;
  /// The rows with an entry of P or Q in a column of eta_mu_list (when dense).
  std::vector<unsigned int> eta_mu_rows;
  bool eta_mu_dense = false, N_eta_mu_valid = false;
  FixedConstraintSchur::SubsetFactor N_eta_mu;
  mutable std::vector<double> gathered; ///< solve()'s workspace on eta_mu_list

  /// The local solves' subset R and its members with eta and mu; the
  /// subsets whose dense factors P and N hold (P.factorize_subset(),
  /// N.factorize_subset(): their entries do not change, so equal subsets
  /// keep them).
  struct LocalBlock
  {
    std::vector<unsigned int> subset, eta_mu, seeds;
    std::vector<unsigned int> factorised_subset, factorised_eta_mu;
    bool factorised = false;
    FixedConstraintSchur::SubsetFactor P_factor, N_factor;
    std::vector<bool> reached; ///< local_subset()'s flags (all false between calls)
    std::vector<double> eta_full, mu_full; ///< full-m scratch, 0 off eta_mu
    std::vector<double> rhs, eta, mu;      ///< on subset, on eta_mu
  };
  LocalBlock local;
  unsigned int settled_count = 0;
};
} // namespace pantocat
