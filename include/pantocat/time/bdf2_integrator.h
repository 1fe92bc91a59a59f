#pragma once

#include <pantocat/lac/sparse_direct_solver.h>
#include <pantocat/system/pattern_operators.h>
#include <pantocat/time/active_set.h>
#include <pantocat/time/constraint_evaluator.h>
#include <pantocat/time/damping_over_mass.h>
#include <pantocat/time/ggl_fixed_block.h>
#include <pantocat/time/impact_projection.h>
#include <pantocat/time/integrator_registry.h>
#include <pantocat/constrained_fast/iteration_matrix.h>
#include <pantocat/constrained_fast/mass_inverse.h>
#include <pantocat/time/time_integrator.h>

#include <deal.II/lac/full_matrix.h>

#include <array>
#include <memory>

namespace pantocat
{
/**
 * Two-step BDF on the GGL-stabilised index-2 formulation (38) (Sec. 5.2),
 * with the Richardson start of Sec. 5.2 (backward Euler with dt and twice
 * dt/2, extrapolated) and the active-set strategy of Sec. 5.3.
 *
 * With the BDF derivative D_h x = c x_{n+1} - rho_x (BDF2: c = 3/(2 dt),
 * rho = (4 x_n - x_{n-1})/(2 dt); Euler: c = 1/dt, rho = x_n/dt), every step
 * solves the linear system
 *
 *   M (D_h q - v) = G_t^T eta + G^T mu,   M (D_h v - a) = G^T eta,
 *   M a + D v + K q = f + G^T lambda,
 *   g = 0, dg/dt = 0, d2g/dt2 = 0 (active constraints, rows at t_{n+1}).
 *
 * Block elimination (doc/dynamics.md) gives, with Y = M^-1 G^T and
 * Z = M^-1 G_t^T of each constraint,
 *
 *   q = q0 + sum_l lambda_l X^lambda_l + eta_l X^eta_l + mu_l X^mu_l,
 *   v = c q - rho_q - sum_l (eta_l Z_l + mu_l Y_l),
 *   a = c v - rho_v - sum_l eta_l Y_l,
 *
 * where q0 = S^-1 (f + M (rho_v + c rho_q) + D rho_q) and the columns
 * X^lambda = S^-1 G^T, X^eta = S^-1 (G^T + c G_t^T + D Z),
 * X^mu = S^-1 (c G^T + D Y) come from the constant matrix
 * S = K + c D + c^2 M, factorised once per c. The columns of the moving
 * contacts are computed at every step, in one batched substitution with the
 * base solve. The constraints with constant rows (droppers, supports) form
 * a block of the multiplier system that GglFixedBlock solves in O(m) by
 * banded Schur complements, factorised when the active set changes; the
 * contacts and the touching fixed constraints border it. A step costs
 * O(n + m). A fixed constraint that held at both history points of a BDF-2
 * step keeps levels 1 and 2 from its level 0 alone (the BDF weights sum to
 * c): its eta and mu vanish in exact arithmetic, and the block takes its
 * lambda alone (settled, GglFixedBlock::select()), which spares their
 * columns' passes.
 *
 * Compliant constraints (Constraint::is_compliant) are implicit forces at
 * t_{n+1}: an engaged one adds its lambda (column X^lambda) and the row
 * lambda/k + g + (c/k) dg/dt = 0 to the multiplier system (the compliance
 * 1/k on its diagonal, S untouched); a disengaged one has lambda = 0. The
 * engaged set starts from the previous step's and is iterated with the
 * active set (ActiveSetIteration): engaged at t_{n+1} iff g < 0 and
 * -k g - c dg/dt > 0 there.
 *
 * Impacts (Sec. 5.3, restitution 0). A constraint that closes in a step is
 * left out of it; at t_{n+1} the positions and velocities are projected onto
 * g = dg/dt = 0 of the holding constraints (ImpactProjection), which gives
 * the impulse [N s] (DynamicState::impulse). Held by the GGL multipliers
 * instead, a closing moving contact (G_t != 0) would be stopped partly by
 * mu through G_t q rather than by a jump of the velocities. Since the BDF-2
 * history would span the jump, the step after an impact is the Richardson
 * start again, from the state after it.
 */
class Bdf2Integrator : public TimeIntegrator
{
public:
  /// Its entry in registered_integrators().
  static IntegratorEntry registry_entry();

  Bdf2Integrator(const SemiDiscreteSystem& system, double time_step,
                 unsigned int max_active_set_iterations,
                 LinearSolverType linear_solver = LinearSolverType::banded);
  ~Bdf2Integrator() override;

  std::string name() const override { return "bdf2"; }
  void initialize(const DynamicState& initial) override;
  void advance() override;
  const DynamicState& latest() const override { return current; }

  /// Settled fixed constraints take lambda alone (true, the default) or all
  /// three multipliers (false: the GGL block in full, for the tests).
  void settle_fixed_constraints(bool on) { settling = on; }
  /// Number of fixed constraints that were settled in the latest step's last trial.
  unsigned int settled_in_latest_step() const { return settled_count; }
  /// The border columns (moving contacts, touching constraints) are solved
  /// with the fixed block on the constraints they reach (true, the default:
  /// GglFixedBlock::solve_local()) or over the whole block (false, for the tests).
  void solve_border_locally(bool on) { border_locally = on; }
  /// Size of the latest step's last local border solve (0: solved whole, or no border).
  unsigned int local_border_size() const { return local_size; }
  double time() const override { return current.t; }
  /// x_n, x_{n-1} (with J_n), the step number (the Richardson start is step 0) and
  /// the counters.
  void save(CheckpointOut& archive) const override;
  void load(CheckpointIn& archive) override;

private:
  struct Stage;          ///< factorisation and constant columns for one value of c
  struct TrialWorkspace; ///< the vectors of a step, kept from step to step
  /// A fixed row k that a border constraint's columns S^-1 (by_columns) or
  /// M^-1 (by_mass_columns) reach.
  struct Reached
  {
    unsigned int k;
    bool by_columns, by_mass_columns;
  };

  /// One implicit step from history (rho_q, rho_v) to time t1 with stage @p s
  /// (into @p storage's vectors, if it has them); `history` must hold
  /// rho_v + c rho_q (form_history(), or the BDF-2 step's pass). With
  /// @p held_before (the flags of x_{n-1} of a BDF-2 step whose history the
  /// steps made), a fixed constraint that holds at t_n and t_{n-1} is settled
  /// (GglFixedBlock::select()); without it none is.
  DynamicState implicit_step(Stage& s, const dealii::Vector<double>& rho_q,
                             const dealii::Vector<double>& rho_v, double t1,
                             const std::vector<bool>& active_at_start,
                             const std::vector<bool>* held_before = nullptr,
                             DynamicState storage = {});
  /**
   * The start of Sec. 5.2: backward Euler with dt (x_dt) and twice with dt/2
   * (x_{dt/2}), each with its own active-set iteration (Sec. 5.3), and the
   * Richardson extrapolation 2 x_{dt/2} - x_dt where both solve the same
   * equations (the same constraints hold and carry force, an impact in both
   * or in neither) and the extrapolated state is consistent itself
   * (satisfies_unilateral_constraints()); else x_{dt/2}. After an impact the
   * two Euler results need not be close: with a touching constraint in one
   * and a force lambda in the other, or a force that falls to zero within
   * the step, the extrapolation gave negative forces (-2 lambda).
   */
  void richardson_start();
  /**
   * Sec. 5.3's test of a step's result @p x: every active rigid unilateral
   * constraint has lambda_i >= 0, every inactive one g_i(t, q) >= 0 (rows at
   * x.t).
   */
  bool satisfies_unilateral_constraints(const DynamicState& x);
  /// history = rho_v + c rho_q.
  void form_history(double c, const dealii::Vector<double>& rho_q,
                    const dealii::Vector<double>& rho_v);
  /**
   * One trial of the active-set iteration: the multipliers of the current
   * sets (the fixed block GglFixedBlock bordered by the moving and touching
   * constraints) and q, v, a of the step into @p x.
   */
  void solve_trial(Stage& s, const std::vector<ConstraintState>& rows,
                   const dealii::Vector<double>& rho_q,
                   const dealii::Vector<double>& rho_v, DynamicState& x);

public:
  /**
   * The next BDF-2 step's history, formed in a step's last pass over q, v, a
   * (combine_trial) instead of a pass of its own at the next step: rho_q =
   * f q_{n+1} + fp q_n, rho_v likewise, h = rho_v + (c + mu) rho_q with mu of
   * each block of the damping split (PatternOperators::shifts()).
   */
  struct NextHistory
  {
    const double *q_n, *v_n;
    double f, fp;
    double *rho_q, *rho_v, *h;
    const std::vector<PatternOperators::Shift>* blocks;
    double c;
  };

private:
  /// A border unknown's share of q, v, a: f times its column X (stride
  /// InterleavedColumns::width), and its mass columns U (Y, Z) with the
  /// factors its kind gives them in v (Y for mu, Z for eta) and a (Y for eta).
  struct BorderTerm
  {
    const double* X;
    const double* U;
    double f, v_Y, v_Z, a_Y;
  };
  /**
   * q += sum of the border terms on the rows @p reach that their columns
   * reach, then v = c q - rho_q - (v + their mass columns), a = c v - rho_v -
   * (a + theirs) in one pass over the unknowns (v and a hold u1, u2 of (38)'s
   * BDF form on entry). With @p from_base, q holds the base solution on
   * entry (its vector taken from the stage) and v, a nothing: q adds the
   * fixed forces' @p sums (if any, zeroed on the way), u1 and u2 start from
   * their sums or 0; off the reach q, v and a are formed in that same pass.
   * With @p next, the last pass also forms the next step's history.
   */
  static void combine_trial(const std::vector<BorderTerm>& terms, const RowRanges& reach,
                            double c, const dealii::Vector<double>& rho_q,
                            const dealii::Vector<double>& rho_v, bool from_base,
                            const GglFixedBlock::ForceSums* sums, const NextHistory* next,
                            DynamicState& x);

  double dt;
  LinearSolverType linear_solver;
  MassInverse mass_inverse;
  DampingOverMass damping_over_mass;
  PatternOperators operators;
  ConstraintEvaluator at_next;
  ActiveSetIteration active_set;
  ImpactProjection impacts;
  std::unique_ptr<Stage> bdf2;
  std::unique_ptr<Stage> start_full, start_half; ///< c = 1/dt, 2/dt of the start
  std::unique_ptr<TrialWorkspace> work;
  /// The last step had an impact: the next one is a Richardson start.
  bool restart = false;
  DynamicState previous, current;
  DynamicState spare; ///< x_{n-2}: its vectors' memory for the next step
  /// Workspace of a step: rho_q, rho_v of the BDF-2 step, rho_v + c rho_q
  /// (+ mu rho_q of the damping split).
  dealii::Vector<double> step_rho_q, step_rho_v, history;
  /// The next step's rho_q, rho_v and history, formed by the step's last pass.
  dealii::Vector<double> next_rho_q, next_rho_v, next_h;
  /// step_rho_q, step_rho_v and history hold the next BDF-2 step's (formed by
  /// the last step; false after a start, an impact or a checkpoint's load).
  bool history_ready = false;
  /// The request of the BDF-2 step under way (advance()), else nullptr.
  const NextHistory* next_history = nullptr;
  unsigned long step_number = 0;
  bool settling = true;                           ///< settle_fixed_constraints()
  unsigned int settled_count = 0;                 ///< settled_in_latest_step()
  bool border_locally = true;                     ///< solve_border_locally()
  unsigned int local_size = 0;                    ///< local_border_size()
  std::vector<std::array<double, 3>> base_levels; ///< g, dg/dt, d2g/dt2 of the base
  /// base_levels[k] holds all three levels (else g alone: a constant row
  /// that held at the history points, whose other levels a trial may not read).
  std::vector<char> levels_complete;
  std::vector<BorderTerm> border_terms; ///< workspace of solve_trial()
};
} // namespace pantocat
