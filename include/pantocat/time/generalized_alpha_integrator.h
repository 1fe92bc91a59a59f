#pragma once

#include <pantocat/lac/interleaved_columns.h>
#include <pantocat/lac/sparse_direct_solver.h>
#include <pantocat/system/pattern_operators.h>
#include <pantocat/time/active_set.h>
#include <pantocat/time/constraint_evaluator.h>
#include <pantocat/constrained_fast/fixed_constraint_schur.h>
#include <pantocat/time/impact_projection.h>
#include <pantocat/time/integrator_registry.h>
#include <pantocat/constrained_fast/iteration_matrix.h>
#include <pantocat/constrained_fast/mass_inverse.h>
#include <pantocat/time/time_integrator.h>

#include <deal.II/lac/full_matrix.h>

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
 * The positions satisfy the constraints exactly (index 3). The velocities are
 * then projected onto the hidden constraints dg/dt = 0 of the active set,
 * v <- v + M^-1 G^T eta, so that both residuals stay at round-off like those
 * of the GGL methods (38), and a constraint that closes in a step (Sec. 5.3)
 * closes with an inelastic impact. Unilateral constraints switch by the
 * active-set strategy of Sec. 5.3.
 *
 * Impacts (Sec. 5.3, restitution 0). The index-3 multiplier lambda of a
 * constraint closing in a step would stop its approach within the step, as a
 * force of order 1/h that overshoots the momentum and pulls on its
 * neighbours (the contact would open for a step at a dropper's re-tension).
 * A closing constraint therefore touches (ActiveSetIteration): it carries no
 * lambda; the positions are projected onto g = 0 of the holding constraints
 * (q <- q + M^-1 G^T mu, after the Newmark relations have given v and a from
 * q before the projection), and the velocities onto dg/dt = 0 with
 * complementary impulses [N s] (ImpactProjection, DynamicState::impulse). The
 * pseudo-acceleration restarts from the acceleration of the end state with
 * the holding constraints held, a = a_c (as at t_0;
 * ImpactProjection::restart_acceleration()); the forces reported at the
 * impact's time point are the step's.
 *
 * Compliant constraints (Constraint::is_compliant) are implicit forces at
 * t_{n+1}: with q = q0 + sum_l lambda_l S^-1 G_l^T and
 * v = v^ + c_v (q - q^), an engaged one adds the row
 * lambda/k + g + (c/k) dg/dt = 0 to the multiplier system, i.e.
 * (G S^-1 G^T + C) lambda = ... with the compliance on the diagonal (S is not
 * refactorised); they take no part in the velocity projection. Their
 * engagement (g < 0 and -k g - c dg/dt > 0 at t_{n+1}) is iterated with the
 * active set (ActiveSetIteration).
 *
 * Linear algebra, O(n + m) per step. S = K + gamma/(beta h) D +
 * (1 - alpha_m)/((1 - alpha_f) beta h^2) M is factorised once. The
 * constraints with constant rows (droppers, supports) enter through their
 * Schur complements G_F S^-1 G_F^T + C and G_F M^-1 G_F^T
 * (FixedConstraintSchur: computed once, sparse, factorised per active set)
 * and their truncated columns S^-1 G^T, M^-1 G^T. A step solves for the base
 * solution and the columns S^-1 G^T, S^-1 G_t^T, M^-1 G^T of the moving
 * contacts in one batched substitution; the contacts border the fixed
 * block (solve_bordered()).
 */
class GeneralizedAlphaIntegrator : public TimeIntegrator
{
public:
  /// Its entry in registered_integrators().
  static IntegratorEntry registry_entry();

  GeneralizedAlphaIntegrator(const SemiDiscreteSystem& system, double time_step,
                             double rho_infinity, unsigned int max_active_set_iterations,
                             LinearSolverType linear_solver = LinearSolverType::banded);

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
  /// Columns S^-1 G^T, S^-1 G_t^T (columns 0, 1 of the S batch) and M^-1 G^T
  /// (column 0 of the M batch) of moving constraint number @p c.
  void compute_moving_columns(unsigned int c, const ConstraintState& r);
  /// The Schur complements and truncated columns of the fixed constraints, once.
  void initialize_fixed(const std::vector<ConstraintState>& rows);
  /**
   * The multipliers of the active rigid and the engaged compliant
   * constraints for the current trial set: g = 0, respectively
   * lambda/k + g + d dg/dt = 0 at t_{n+1}, with q = q0 + S^-1 G^T lambda.
   */
  void solve_position_level(const std::vector<ConstraintState>& rows,
                            std::vector<double>& lambda);
  /// q = q0 + S^-1 G^T lambda (truncated columns of the fixed constraints); q
  /// takes the base solution's vector (S.base is left with q's old one).
  void assemble_positions(const std::vector<double>& lambda, dealii::Vector<double>& q);
  /**
   * x <- x + M^-1 G^T y with residual(i) + G_i M^-1 G^T y = 0 on the
   * constraints that hold (active and touching): the projection of the
   * positions (residual g) or of the velocities (residual dg/dt). Returns y
   * per constraint (0 elsewhere) in @p multipliers.
   */
  template <typename Residual>
  void project(const std::vector<ConstraintState>& rows, double t1, Residual residual,
               dealii::Vector<double>& x, std::vector<double>& multipliers,
               const char* what);

  double h;
  Coefficients k;
  double c_q, c_v; ///< S = K + c_v D + c_q M
  MassInverse mass_inverse;
  IterationMatrix S;          ///< K + c_v D + c_q M and the column batches
  PatternOperators operators; ///< f + M h + E r with the damping split for S
  ConstraintEvaluator at_next;
  ActiveSetIteration active_set;
  ImpactProjection impacts; ///< velocities at an impact
  DynamicState current;
  dealii::Vector<double> pseudo_acceleration;
  unsigned long step_number = 0;
  /// G_F S^-1 G_F^T + C (C: the compliance of engaged elastic droppers) and
  /// G_F M^-1 G_F^T of the fixed constraints.
  FixedConstraintSchur fixed_S, fixed_M;
  bool fixed_ready = false;
  /// The parts c_q q^ - w + mu (c_v q^ - v^) and c_v q^ - v^ of the
  /// right-hand side (workspace of a step; the predictors q^, v^ and w =
  /// (alpha_m a_n - alpha_f a_c,n) / (1 - alpha_f) are not stored: each pass
  /// forms them from x_n; the base solution q0 is S.base).
  dealii::Vector<double> mass_part, damping_part;
  /// Per constraint at t_{n+1} for q = q0, v = v^ + c_v (q0 - q^): g and dg/dt.
  std::vector<double> base_gap, base_rate;
  /// G q^ and G v^ of every constraint (the rates of the step's trials).
  std::vector<double> G_q_hat, G_v_hat;
  /// Per constraint: compliant (its rate enters its law and accept()); the
  /// rates and G q^, G v^ of the others are not formed (0).
  std::vector<char> with_rate;
  std::vector<double> ratio; ///< damping_ratio() of each constraint, read once
  /// The rows G of the fixed constraints, one after the other
  /// (FixedConstraintSchur order): the dots of a step read them in one
  /// stream.
  CompressedRows fixed_G;
  /// The fixed constraints on each unknown: those a moving column's reach
  /// meets (the others' products with it are +0).
  RowsByColumn fixed_at_row;
  std::vector<unsigned int> reached; ///< the fixed constraints a column reaches
  std::vector<char> seen;            ///< RowsByColumn::rows_in()'s workspace
  std::vector<bool> keep;            ///< fixed constraints in the current system
  std::vector<double> factors;       ///< their multipliers (FixedConstraintSchur order)
  /// mu of the position projection (touching constraints) and eta of the
  /// velocity projection, per constraint.
  std::vector<double> position_multipliers, velocity_multipliers;
  dealii::Vector<double> q_newmark; ///< q_{n+1} before the position projection
  /// The state before current and the pseudo-acceleration before the
  /// current one: their vectors' memory for the next step's.
  DynamicState spare;
  dealii::Vector<double> next_pseudo_acceleration;
  std::vector<double> gaps, rates; ///< of a trial, per constraint
  /// The bordered systems of solve_position_level() and project(), kept from
  /// step to step (nothing allocated once their sizes are reached).
  struct Bordered
  {
    std::vector<unsigned int> moving_in; ///< the moving constraints in the system
    dealii::Vector<double> x, y, rhs;
    std::vector<dealii::Vector<double>> Bc, Cr;
    dealii::FullMatrix<double> D;
    std::vector<dealii::Vector<double>*> batch;
    std::vector<double> fixed_part;
    /// x, Bc, Cr: mF zeros each (p columns); y: p zeros; D: p x p zeros.
    void reinit(unsigned int mF, unsigned int p);
  } bordered;
};
} // namespace pantocat
