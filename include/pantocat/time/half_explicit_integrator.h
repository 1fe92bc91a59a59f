#pragma once

#include <pantocat/constrained/half_explicit_step_system.h>
#include <pantocat/time/active_set.h>
#include <pantocat/time/constraint_evaluator.h>
#include <pantocat/time/impact_projection.h>
#include <pantocat/time/integrator_registry.h>
#include <pantocat/time/time_integrator.h>

#include <memory>

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
 * How the two levels are solved (the linear algebra of W = M + dt/2 D and
 * M, the multiplier systems) is HalfExplicitStepSystem's business; the
 * method states the step, the active-set strategy, the compliant forces and
 * the impacts.
 *
 * Compliant constraints (Constraint::is_compliant) are explicit forces: in
 * step 1, lambda_i = max(0, -k g_i - c dg_i/dt) (unilateral, 0 when g_i >= 0)
 * or -k g_i - c dg_i/dt (bilateral) from q_n and the damping velocity
 * (v_{n-1} + v_n)/2 of (41), and G_i^T lambda_i joins the force of (39); they
 * are never in the active set. The method is then stable for dt < 2/omega_max
 * of K + sum k_i G_i^T G_i (largest_circular_frequency).
 *
 * The first step needs v_{-1}: v_0 - dt a_0 (one Euler step back; the method
 * stays second order).
 *
 * Impacts (Sec. 5.3, restitution 0): the step t_n -> t_{n+1} is taken
 * without a constraint that closes in it (it had no contact at t_n, so no
 * force lambda_n); q_{n+1}, v_{n+1} are then projected onto g = dg/dt = 0 of
 * the holding constraints (ImpactProjection), whose impulses [N s] are
 * reported with t_{n+1} (DynamicState::impulse), and the jump of the
 * velocities is added to v_n as well, which the two-step update of the next
 * step starts from.
 *
 * With D = 0 the map
 * (v_{n-1}, q_n, v_n) -> (v_n, q_{n+1}, v_{n+1}) is reversible: stepping with -dt from
 * (v_{n+1}, q_{n+1}, v_n) returns (v_n, q_n, v_{n-1}).
 */
class HalfExplicitIntegrator : public TimeIntegrator
{
public:
  /// Its entry in registered_integrators().
  static IntegratorEntry registry_entry();

  /// With the step system of @p algebra.
  HalfExplicitIntegrator(const SemiDiscreteSystem& system, double time_step,
                         unsigned int max_active_set_iterations,
                         LinearAlgebra algebra = LinearAlgebra::fast);
  /// With @p levels (its time_step() is dt), e.g. a fast one set up by a test.
  HalfExplicitIntegrator(const SemiDiscreteSystem& system,
                         std::unique_ptr<HalfExplicitStepSystem> levels,
                         unsigned int max_active_set_iterations,
                         LinearAlgebra algebra = LinearAlgebra::fast);

  std::string name() const override { return "half-explicit"; }
  void initialize(const DynamicState& initial) override;
  void advance() override;
  void finish() override;
  const DynamicState& latest() const override { return reported; }
  /// The rows of step 1 (at t_n = latest().t), evaluated by advance() and finish().
  const std::vector<ConstraintState>* constraint_states_at_latest() const override
  {
    return at_n.holds(reported.t) ? &at_n.states() : nullptr;
  }
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
  const dealii::Vector<double>& previous_velocities() const { return *previous; }

private:
  /**
   * lambda_n of the compliant constraints (explicit forces of (39), from
   * q_n and the damping velocity (v_{n-1} + v_n)/2 of (41)), and their
   * engagement in active_now.
   */
  void compute_compliant_forces();
  /// The rows at t_n, t_{n+1/2}, t_{n+1} and the step system's start.
  void start_step();
  /// Step 1 (39), (41) on @p force_set, then step 2 (40) on @p active_set_of_step.
  void trial(const std::vector<unsigned int>& force_set,
             const std::vector<unsigned int>& active_set_of_step);
  /// After a step in which a constraint closed: q_{n+1}, v_{n+1} projected.
  void impact(std::vector<double>& impulse, std::vector<unsigned int>& separated);
  /// Reports t_n and moves on to t_{n+1}.
  void move_on(bool impact, std::vector<double>& impulse,
               const std::vector<unsigned int>& separated);

  double dt;
  double t = 0.;
  unsigned long step_number = 0;
  std::unique_ptr<HalfExplicitStepSystem> levels; ///< (39), (40) of a step
  dealii::Vector<double> q, v, v_prev, a, q_new, v_new;
  /**
   * v_{n-1}: v_prev after initialize(), set_previous_velocity() and load(),
   * afterwards reported.v (v_n of the step before is both), which saves a
   * copy of a vector per step. The integrator is not copied or moved.
   */
  dealii::Vector<double>* previous = &v_prev;
  ConstraintEvaluator at_n, at_half, at_next;
  ActiveSetIteration active_set;
  std::unique_ptr<ConstrainedOperator> M; ///< of the impacts' projections
  ImpactProjection impacts;               ///< after a step in which a constraint closed
  std::vector<bool> active_now;           ///< J_n
  std::vector<double> lambda, gaps;
  /// The impulses of the impact at t_{n+1} (reported with t_{n+1}), or empty.
  std::vector<double> pending_impulse;
  dealii::Vector<double> jump;         ///< v+ - v- of an impact
  std::vector<unsigned int> compliant; ///< indices of the compliant constraints
  unsigned long history_start = 0;     ///< the step of the latest start or new v_{n-1}
  DynamicState reported;
};
} // namespace pantocat
