#pragma once

#include <pantocat/lac/interleaved_columns.h>
#include <pantocat/lac/sparse_direct_solver.h>
#include <pantocat/system/pattern_operators.h>
#include <pantocat/time/active_set.h>
#include <pantocat/time/constraint_evaluator.h>
#include <pantocat/time/integrator_registry.h>
#include <pantocat/time/iteration_matrix.h>
#include <pantocat/time/mass_inverse.h>
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
 * active-set strategy of Sec. 5.3, without the touching state of
 * ActiveSetIteration (index 3 has no position-level multiplier besides
 * lambda to hold a constraint without force).
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
 * Linear algebra as in Bdf2Integrator: S = K + gamma/(beta h) D +
 * (1 - alpha_m)/((1 - alpha_f) beta h^2) M is factorised once; a step solves
 * for the base solution and the columns S^-1 G^T, M^-1 G^T of the moving
 * contact in one batched substitution.
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
  /// Columns X = S^-1 G^T (in the column `lambda` of the S batch) and
  /// Y = M^-1 G^T of constraint l.
  void compute_columns(unsigned int l, const ConstraintState& r);

  double h;
  Coefficients k;
  double c_q, c_v; ///< S = K + c_v D + c_q M
  MassInverse mass_inverse;
  IterationMatrix S; ///< K + c_v D + c_q M and the column batches
  PatternOperators operators;
  ConstraintEvaluator at_next;
  ActiveSetIteration active_set;
  DynamicState current;
  dealii::Vector<double> pseudo_acceleration;
  unsigned long step_number = 0;
  dealii::FullMatrix<double> small;
  dealii::Vector<double> small_rhs, small_solution;
  std::vector<unsigned int> unknowns; ///< active rigid, then engaged compliant
};
} // namespace pantocat
