#pragma once

#include <pantocat/constrained/implicit_step_system.h>
#include <pantocat/constrained_fast/damping_over_mass.h>
#include <pantocat/constrained_fast/ggl_fixed_block.h>
#include <pantocat/constrained_fast/mass_inverse.h>
#include <pantocat/lac/local_columns.h>
#include <pantocat/system/pattern_operators.h>

#include <deal.II/lac/vector.h>

#include <array>
#include <memory>
#include <vector>

namespace pantocat
{
/**
 * The structured ImplicitStepSystem, O(n + m) per solve. With
 * Y = M^-1 G^T and Z = M^-1 G_t^T of each constraint,
 *
 *   q = q0 + sum_l lambda_l X^lambda_l + eta_l X^eta_l + mu_l X^mu_l,
 *   v = c q - rho_q - sum_l (eta_l Z_l + mu_l Y_l),
 *   a = c v - rho_v - sum_l eta_l Y_l,
 *
 * where q0 = S^-1 (f + M (rho_v + c rho_q) + D rho_q) and the columns
 * X^lambda = S^-1 G^T, X^eta = S^-1 (G^T + c G_t^T + D Z),
 * X^mu = S^-1 (c G^T + D Y) come from S = K + c D + c^2 M, factorised once.
 * The columns of the moving constraints (contacts) are solved at every
 * start(), on the rows they reach. The constraints with constant rows
 * (droppers, supports) form a block of the multiplier system that
 * GglFixedBlock solves in O(m) by banded Schur complements, factorised when
 * the active set changes; the contacts and the touching fixed constraints
 * border it, their border solved on the fixed constraints they reach
 * (GglFixedBlock::local_subset()). A fixed constraint that held at every
 * history point (start()'s @p held) and that no border's mass columns reach
 * takes lambda alone (settled: GglFixedBlock::select()). q, v, a (and the
 * next history) are formed in one pass over the unknowns.
 */
class FastImplicitStepSystem : public ImplicitStepSystem
{
public:
  FastImplicitStepSystem(const SemiDiscreteSystem& system, double c,
                         LinearSolverType solver, bool forms_next_history);
  ~FastImplicitStepSystem() override;

  void start(const std::vector<ConstraintState>& rows, double t,
             const dealii::Vector<double>& rho_q, const dealii::Vector<double>& rho_v,
             const std::vector<bool>* held, const NextHistory* next,
             bool continued) override;
  void solve(const std::vector<Role>& roles, dealii::Vector<double>& q,
             dealii::Vector<double>& v, dealii::Vector<double>& a,
             std::vector<double>& lambda) override;
  void take_next_history(dealii::Vector<double>& rho_q,
                         dealii::Vector<double>& rho_v) override;

  /// Settled fixed constraints take lambda alone (true, the default) or all
  /// three multipliers (false: the block in full, for the tests).
  void settle_fixed_constraints(bool on) { settling = on; }
  /// Number of fixed constraints settled in the latest solve().
  unsigned int settled_in_latest_solve() const { return settled_count; }
  /// The border is solved with the fixed block on the constraints it reaches
  /// (true, the default) or over the whole block (false, for the tests).
  void solve_border_locally(bool on) { border_locally = on; }
  /// Size of the latest solve()'s local border solve (0: solved whole, or no border).
  unsigned int local_border_size() const { return local_size; }
  /// Number of solve() calls so far.
  unsigned long solves() const { return solve_count; }

  /**
   * The next history in a solve's last pass over q, v, a: rho_q = f q_{n+1}
   * + fp q_n, rho_v likewise, h = rho_v + (c + mu) rho_q with mu of each
   * block of the damping split (PatternOperators::shifts()).
   */
  struct HistoryPass
  {
    const double *q_n, *v_n;
    double f, fp;
    double *rho_q, *rho_v, *h;
    const std::vector<PatternOperators::Shift>* blocks;
    double c;
  };

  /// A border unknown's share of q, v, a: f times its column X (stride
  /// InterleavedColumns::width), and its mass columns U (Y, Z) with the
  /// factors its kind gives them in v (Y for mu, Z for eta) and a (Y for eta).
  struct BorderTerm
  {
    const double* X;
    const double* U;
    double f, v_Y, v_Z, a_Y;
  };

  /// A border unknown (kind: lambda, eta, mu) or equation (level 0, 1, 2 or
  /// the force law, 3) of one constraint.
  struct Slot
  {
    unsigned int constraint, kind;
  };

private:
  using Levels = std::array<double, 3>; ///< g, dg/dt, d2g/dt2 of a row
  struct Stage;          ///< S, its factorisation and the constraints' columns
  struct TrialWorkspace; ///< the vectors of a solve, kept from step to step
  /// A fixed row k that a border constraint's columns S^-1 (by_columns) or
  /// M^-1 (by_mass_columns) reach.
  struct Reached
  {
    unsigned int k;
    bool by_columns, by_mass_columns;
  };

  /// The base solution q0 into the stage (again after a solve took it).
  void solve_base();
  /// The levels g, dg/dt, d2g/dt2 of the base solution on every row.
  void base_levels_of_rows(const std::vector<bool>* held);
  /// The multipliers of @p roles and q, v, a of the solution, in the steps below.
  void solve_trial(const std::vector<Role>& roles, dealii::Vector<double>& q,
                   dealii::Vector<double>& v, dealii::Vector<double>& a,
                   std::vector<double>& forces);
  /// The fixed constraints in the block (with force or engaged) and the
  /// border's unknowns and equations (moving and touching constraints).
  void classify(const std::vector<Role>& roles);
  /// The fixed rows each border constraint reaches; the block's selection
  /// with the settled constraints (GglFixedBlock::select()).
  void select_block(const std::vector<Role>& roles);
  /// The block's right-hand side: minus the base levels of its rows.
  void block_right_hand_side();
  /// The fixed rows against the border columns (Bc).
  void border_columns();
  /// The border rows against the fixed unknowns (Cr) and the border (D, y).
  void border_rows();
  /// The truncated fixed columns' products with @p row (X0, ..., Y1), and
  /// the fixed columns that reach it.
  void fixed_columns_on_row(const ConstraintState& row);
  /// Border equation @p e against every unknown, and its right-hand side.
  void border_row(unsigned int e);
  /// The bordered system, on the block's local subset where it has one.
  void solve_bordered_system();
  /// lambda of every constraint; the fixed ones' sums of multipliers.
  void multipliers(std::vector<double>& forces);
  /// q, v, a from the base, the fixed forces and the border terms.
  void form_solution(dealii::Vector<double>& q, dealii::Vector<double>& v,
                     dealii::Vector<double>& a);
  /// The border unknowns' terms and the rows they reach.
  void border_terms_of_solution();
  /// Levels of row @p k against the columns of border unknown @p u.
  Levels border_levels(unsigned int k, const Slot& u) const;
  /// Equation @p e's value of levels @p L (a level, or the force law's).
  double value(const Levels& L, const Slot& e) const;
  /// Fixed row @p k's levels @p L in the block's equation slots of @p v.
  void fixed_slots(unsigned int k, const Levels& L, dealii::Vector<double>& v) const;
  /// The base levels of row @p i, completed if start() left them at g.
  const Levels& levels_of(unsigned int i);
  /**
   * q += sum of the border terms on the rows @p reach that their columns
   * reach, then v = c q - rho_q - (v + their mass columns), a = c v - rho_v -
   * (a + theirs) in one pass over the unknowns (v and a hold u1, u2 on
   * entry). With @p from_base, q holds the base solution on entry and v, a
   * nothing: q adds the fixed forces' @p sums (if any, zeroed on the way),
   * u1 and u2 start from their sums or 0; off the reach q, v and a are formed
   * in that same pass. With @p next, the last pass also forms the next
   * history.
   */
  static void combine_trial(const std::vector<BorderTerm>& terms, const RowRanges& reach,
                            double c, const dealii::Vector<double>& rho_q,
                            const dealii::Vector<double>& rho_v, bool from_base,
                            const GglFixedBlock::ForceSums* sums, const HistoryPass* next,
                            dealii::Vector<double>& q, dealii::Vector<double>& v,
                            dealii::Vector<double>& a);

  MassInverse mass_inverse;
  DampingOverMass damping_over_mass;
  PatternOperators operators;
  std::unique_ptr<Stage> stage;
  std::unique_ptr<TrialWorkspace> work;
  const bool split; ///< the damping split of forms_next_history
  /// One block of all rows without a damping split (HistoryPass::blocks).
  const std::vector<PatternOperators::Shift> whole_rows;

  /// rho_v + c rho_q (+ mu rho_q of the damping split); history_ready: formed
  /// by the last solve with the vectors take_next_history() handed out.
  dealii::Vector<double> history, next_rho_q, next_rho_v, next_h;
  bool history_ready = false;
  bool base_taken = false; ///< a solve took the base's vector for q

  bool settling = true;
  unsigned int settled_count = 0;
  bool border_locally = true;
  unsigned int local_size = 0;
  unsigned long solve_count = 0;
  std::vector<Levels> base_levels; ///< of the base solution
  /// base_levels[k] holds all three levels (else g alone: a constant row
  /// that held at the history points, whose other levels a solve may not read).
  std::vector<char> levels_complete;
  std::vector<BorderTerm> border_terms; ///< workspace of solve_trial()
};
} // namespace pantocat
