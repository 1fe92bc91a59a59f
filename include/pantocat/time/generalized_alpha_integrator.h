#pragma once

#include <pantocat/constrained/constrained_operator.h>
#include <pantocat/time/active_set.h>
#include <pantocat/time/constraint_evaluator.h>
#include <pantocat/time/impact_projection.h>
#include <pantocat/time/integrator_registry.h>
#include <pantocat/time/time_integrator.h>

#include <memory>

namespace pantocat
{
/**
 * The generalized-alpha method of Chung and Hulbert for the constrained
 * second-order system (35), in the form of Arnold and Bruels (2007) for
 * constrained mechanical systems: with the pseudo-acceleration a and the true
 * acceleration a_c,
 *
 *   q_{n+1} = q_n + h v_n + h^2 (1/2 - beta) a_n + h^2 beta a_{n+1},
 *   v_{n+1} = v_n + h (1 - gamma) a_n + h gamma a_{n+1},
 *   (1 - alpha_m) a_{n+1} + alpha_m a_n = (1 - alpha_f) a_c,{n+1} + alpha_f a_c,n,
 *   M a_c,{n+1} + D v_{n+1} + K q_{n+1} = f + G(t_{n+1})^T lambda_{n+1},
 *   g(t_{n+1}, q_{n+1}) = 0 (active constraints),
 *
 * with alpha_m = (2 rho - 1)/(rho + 1), alpha_f = rho/(rho + 1),
 * gamma = 1/2 - alpha_m + alpha_f, beta = (1 - alpha_m + alpha_f)^2 / 4 for
 * the spectral radius rho = rho_inf at infinity: second order, unconditionally
 * stable, high frequencies damped to rho_inf per step; rho_inf = 1 is the
 * trapezoidal rule (no numerical damping).
 *
 * A step in the paper's terms. Eliminating a_{n+1}, a_c,{n+1} and v_{n+1}
 * by the first three lines leaves the linear system of an implicit step,
 *
 *   S q_{n+1} = f(t_{n+1}) + M (c_q q^ - w) + D (c_v q^ - v^) + G^T lambda,
 *   S = K + c_v D + c_q M,  c_q = (1 - alpha_m) / ((1 - alpha_f) beta h^2),
 *   c_v = gamma / (beta h),
 *
 * with the predictors q^ = q_n + h v_n + h^2 (1/2 - beta) a_n,
 * v^ = v_n + h (1 - gamma) a_n and w = (alpha_m a_n - alpha_f a_c,n) /
 * (1 - alpha_f). So q_{n+1} = q0 + S^-1 G^T lambda (q0: the solution without
 * forces), and lambda solves the multiplier system of the position level,
 * G S^-1 G^T lambda = -g(t_{n+1}, q0), on the active set.
 *
 * Projections (index 3 positions, index 2 velocities). The positions satisfy
 * g = 0 exactly; the velocities are then projected onto the hidden
 * constraints dg/dt = 0 of the active set, v <- v + M^-1 G^T eta, so that
 * both residuals stay at round-off like those of the GGL methods (38).
 *
 * Impacts (Sec. 5.3, restitution 0). A constraint closing in a step touches
 * (ActiveSetIteration): it carries no lambda; the positions are projected
 * onto g = 0 of the holding constraints (q <- q + M^-1 G^T mu, after the
 * Newmark relations have given v and a from q before the projection), and
 * the velocities onto dg/dt = 0 with complementary impulses [N s]
 * (ImpactProjection, DynamicState::impulse). The impact changes the
 * velocities only: a_{n+1} and a_c,{n+1} stay those of the step, the smooth
 * part of the motion (as in the nonsmooth generalized-alpha schemes, which
 * keep the impulsive part of the velocity apart from the accelerations).
 * Restarting them from the end state's acceleration M^-1 (f - K q - D v +
 * G^T y) instead fed the impulse's high-frequency content (M^-1 G^T P on the
 * consistent Hermite mass) into the predictor q^: at 48 m/s on FEM the
 * dropper was kicked slack again at every re-tension, worse on finer grids
 * (N+1 = 2000: never re-tensioned, contact forces of 984 N). The forces
 * reported at the impact's time point are the step's.
 *
 * Compliant constraints (Constraint::is_compliant) are implicit forces at
 * t_{n+1}: an engaged one has the law lambda/k + g + d dg/dt = 0 with
 * dg/dt = G_t q + G v + z_t and v = v^ + c_v (q - q^). Divided by
 * (1 + d c_v), its row of the multiplier system is
 * (G + e G_t) S^-1 G^T lambda + C lambda = -(g0 + d r0) / (1 + d c_v) with
 * the compliance C = 1 / (k (1 + d c_v)) and the rate weight
 * e = d / (1 + d c_v) (g0, r0: g and dg/dt at q0). Their engagement is
 * iterated with the active set.
 *
 * Linear algebra: two ConstrainedOperators, S (with the compliant rows'
 * C and e) and M (the projections); how they solve is theirs.
 */
class GeneralizedAlphaIntegrator : public TimeIntegrator
{
public:
  /// Its entry in registered_integrators().
  static IntegratorEntry registry_entry();

  GeneralizedAlphaIntegrator(const SemiDiscreteSystem& system, double time_step,
                             double rho_infinity, unsigned int max_active_set_iterations,
                             LinearSolverType linear_solver = LinearSolverType::banded,
                             LinearAlgebra algebra = LinearAlgebra::fast);

  std::string name() const override { return "generalized-alpha"; }
  void initialize(const DynamicState& initial) override;
  void advance() override;
  const DynamicState& latest() const override { return current; }
  double time() const override { return current.t; }
  /// x_n (with a_c,n and J_n), the pseudo-acceleration a_n and the counters.
  void save(CheckpointOut& archive) const override;
  void load(CheckpointIn& archive) override;

  /// The method's coefficients for rho_inf (Chung and Hulbert 1993).
  struct Coefficients
  {
    double alpha_m, alpha_f, beta, gamma;
    explicit Coefficients(double rho_infinity);
  };

private:
  /// h = c_q q^ - w and r = c_v q^ - v^ of the step's right-hand side
  /// f + M h + D r, with the predictors q^, v^ and w from x_n.
  void predict();
  /// q0 = S^-1 (f(t_{n+1}) + M (c_q q^ - w) + D (c_v q^ - v^)), and g0, r0 at
  /// q0 (with G q^ and G v^ of the compliant constraints).
  void solve_without_forces(const std::vector<ConstraintState>& rows, double t1);
  /// dg/dt of constraint @p i (rows @p row) at t_{n+1} for q, with
  /// v = v^ + c_v (q - q^).
  double newmark_rate(unsigned int i, const ConstraintState& row,
                      const dealii::Vector<double>& q) const;
  /**
   * One trial of the active set: lambda of the position level on the active
   * rigid and engaged compliant constraints, q = q0 + S^-1 G^T lambda, and
   * for touching constraints the position projection (`touching`;
   * q_newmark keeps q before it). Returns true if the active set accepts
   * the trial.
   */
  bool trial(const std::vector<ConstraintState>& rows, double t1, DynamicState& x);
  /// The Newmark relations: a_{n+1} (into next_pseudo_acceleration),
  /// v_{n+1} and a_c,{n+1} from q_{n+1}.
  void newmark_update(const dealii::Vector<double>& q, DynamicState& x);
  /// The velocity projection onto dg/dt = 0, or the impact's (Sec. 5.3).
  void project_velocities(const std::vector<ConstraintState>& rows, double t1,
                          DynamicState& x);

  double h;
  Coefficients k;
  double c_q, c_v; ///< S = K + c_v D + c_q M
  std::unique_ptr<ConstrainedOperator> S, M;
  ConstraintEvaluator at_next;
  ActiveSetIteration active_set;
  ImpactProjection impacts; ///< velocities at an impact, on M
  DynamicState current;
  dealii::Vector<double> pseudo_acceleration; ///< a_n
  unsigned long step_number = 0;
  std::vector<double> ratio; ///< d of each constraint's law (damping_ratio())

  /// Workspace of a step, kept so that a step allocates nothing: the
  /// right-hand side's parts, q0, q before the position projection, a_{n+1},
  /// the state before current (its vectors' memory for the next step's);
  /// per constraint g and dg/dt at q0, G q^ and G v^ (compliant ones), the
  /// gaps and rates of a trial and the position projection's multipliers.
  dealii::Vector<double> mass_part, damping_part, q0, q_newmark, next_pseudo_acceleration;
  DynamicState spare;
  bool touching = false;
  bool q0_current = false; ///< q0 holds the step's solution (a trial takes its vector)
  std::vector<double> base_gap, base_rate, G_q_hat, G_v_hat, gaps, rates,
      position_multipliers;
};
} // namespace pantocat
