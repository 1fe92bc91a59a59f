#pragma once

#include <pantocat/time/active_set.h>
#include <pantocat/time/constraint_evaluator.h>
#include <pantocat/time/integrator_registry.h>
#include <pantocat/time/mass_inverse.h>
#include <pantocat/time/time_integrator.h>

#include <deal.II/lac/full_matrix.h>

namespace pantocat
{
/**
 * The reversible half-explicit two-step method (39)-(41) of Sec. 5.2 for the
 * GGL-stabilised system (38), with the active-set strategy of Sec. 5.3.
 *
 * Given q_n, v_n, v_{n-1}, a step t_n -> t_{n+1} = t_n + dt:
 *  1. (39) with the smoothing (41): (M + dt/2 D) a_n = f - K q_n
 *     - D (v_{n-1} + v_n)/2 + G(t_n)^T lambda_n, and the acceleration-level
 *     constraints g^(II) = 0 of the active set give lambda_n;
 *  2. (40): v_{n+1} = v_{n-1} + 2 dt a_n + 2 dt M^-1 G(t_n)^T eta,
 *     q_{n+1} = q_n + dt (v_n + v_{n+1})/2 + dt M^-1 (G_t(t_{n+1/2})^T eta
 *     + G(t_{n+1/2})^T mu), with eta, mu from g^(0) = g^(I) = 0 at t_{n+1}.
 * Only the multipliers come from small dense systems; the rest are
 * applications of (M + dt/2 D)^-1 and M^-1: diagonal scalings for FDM,
 * solves with factorisations made once for FEM.
 *
 * Compliant constraints (Constraint::is_compliant) are explicit forces: in
 * step 1, lambda_i = max(0, -k g_i - c dg_i/dt) (unilateral, 0 when g_i >= 0)
 * or -k g_i - c dg_i/dt (bilateral) from q_n and the damping velocity
 * (v_{n-1} + v_n)/2 of (41), and G_i^T lambda_i joins the force of (39); they
 * are never in the active set. The method is then stable for dt < 2/omega_max
 * of K + sum k_i G_i^T G_i (largest_circular_frequency).
 *
 * The first step needs v_{-1}: v_0 - dt a_0 (one Euler step back; the method
 * stays second order). With D = 0 the map (v_{n-1}, q_n, v_n) -> (v_n,
 * q_{n+1}, v_{n+1}) is reversible: stepping with -dt from (v_{n+1}, q_{n+1},
 * v_n) returns (v_n, q_n, v_{n-1}).
 */
class HalfExplicitIntegrator : public TimeIntegrator
{
public:
  /// Its entry in registered_integrators().
  static IntegratorEntry registry_entry();

  HalfExplicitIntegrator(const SemiDiscreteSystem& system, double time_step,
                         unsigned int max_active_set_iterations);

  std::string name() const override { return "half-explicit"; }
  void initialize(const DynamicState& initial) override;
  void advance() override;
  void finish() override;
  const DynamicState& latest() const override { return reported; }
  bool multipliers_lag_one_step() const override { return true; }
  double time() const override { return t; }
  /// t_n, q_n, v_n, v_{n-1}, J_n, the last reported point and the counters.
  void save(CheckpointOut& archive) const override;
  void load(CheckpointIn& archive) override;

  /// Replaces v_{n-1} (e.g. to step backwards from (v_{n+1}, q_{n+1}, v_n)).
  void set_previous_velocity(const dealii::Vector<double>& v_previous);
  /// Changes the sign or size of the step (the factorisations are redone if D != 0).
  void set_time_step(double time_step);

  const dealii::Vector<double>& positions() const { return q; }
  const dealii::Vector<double>& velocities() const { return v; }
  const dealii::Vector<double>& previous_velocities() const { return v_prev; }

private:
  /// lambda_n of the compliant constraints (their engagement in active_now), a += Y
  /// lambda.
  void add_compliant_forces();
  /// Step 1: a_n and lambda_n for the active set.
  void compute_acceleration(const std::vector<unsigned int>& active);
  /// Step 2: q_{n+1}, v_{n+1} for the active set; fills the gaps at t_{n+1}.
  void compute_update(const std::vector<unsigned int>& active);
  void compute_time_dependent_columns();
  void reset_time_dependent_columns();
  void factorize();
  /// a <- (M + dt/2 D)^-1 (f - K q - D (v_prev + v)/2), in one pass over the
  /// rows where (M + dt/2 D) is diagonal but for a few coupled rows.
  void compute_forces();
  /// f(t_n): the system's constant load, or f(t_n) in load_now if it depends on t.
  const double* load_at_time_n();

  /// K and D/2 stored by diagonals (offsets -b..b, zero-padded): the
  /// semi-discrete operators are banded within each body, and a diagonal
  /// sweep vectorises. Offsets on which an operator vanishes are skipped.
  struct BandedOperator
  {
    int bandwidth = 0;
    std::vector<int> stiffness_offsets, damping_offsets;
    std::vector<std::vector<double>> stiffness, half_damping; ///< [offset + b][row]
    struct Entry
    {
      unsigned int row, column;
      double value;
    };
    /// D/2 off the diagonal, and on it too if damped_rows_coupled.
    std::vector<Entry> listed_damping;
    /**
     * True when only the rows of a coupled block (a lumped pantograph's) are
     * damped, e.g. a scene without the wires' damping: the sweep then skips
     * the diagonal of D and its two velocity streams, and the list carries
     * every damper.
     */
    bool damped_rows_coupled = false;
    bool symmetric_stiffness = false; ///< K(i, j) == K(j, i) exactly
  } forces;

  double dt;
  double t = 0.;
  unsigned long step_number = 0;
  dealii::Vector<double> q, v, v_prev, a, q_new, v_new;
  dealii::Vector<double> load_now;   ///< f(t_n), only for a time-dependent load
  MassInverse smoothed_mass_inverse; ///< (M + dt/2 D)^{-1}
  MassInverse mass_inverse;          ///< M^{-1}
  ConstraintEvaluator at_n, at_half, at_next;
  ActiveSetIteration active_set;
  std::vector<bool> active_now;
  /// Columns per constraint: Y = (M+dt/2 D)^-1 G(t_n)^T, P = M^-1 G(t_n)^T,
  /// Q = M^-1 G_t(t_{n+1/2})^T, R = M^-1 G(t_{n+1/2})^T.
  std::vector<dealii::Vector<double>> Y, P, Q, R;
  std::vector<double> lambda, gaps;
  std::vector<unsigned int> compliant; ///< indices of the compliant constraints
  dealii::FullMatrix<double> small;
  dealii::Vector<double> small_rhs, small_solution;
  DynamicState reported;
};
} // namespace pantocat
