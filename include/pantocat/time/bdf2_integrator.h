#pragma once

#include <pantocat/constrained/constrained_operator.h>
#include <pantocat/constrained/implicit_step_system.h>
#include <pantocat/time/active_set.h>
#include <pantocat/time/constraint_evaluator.h>
#include <pantocat/time/impact_projection.h>
#include <pantocat/time/integrator_registry.h>
#include <pantocat/time/time_integrator.h>

#include <functional>
#include <memory>

namespace pantocat
{
/**
 * Two-step BDF on the GGL-stabilised index-2 formulation (38) (Sec. 5.2),
 * with the Richardson start of Sec. 5.2 (backward Euler with dt and twice
 * dt/2, extrapolated) and the active-set strategy of Sec. 5.3.
 *
 * With the BDF derivative D_h x = c x_{n+1} - rho_x (BDF-2: c = 3/(2 dt),
 * rho_x = (4 x_n - x_{n-1})/(2 dt); backward Euler: c = 1/dt,
 * rho_x = x_n/dt), every step solves the linear system of (38) at t_{n+1},
 *
 *   M (D_h q - v) = G_t^T eta + G^T mu,   M (D_h v - a) = G^T eta,
 *   M a + D v + K q = f + G^T lambda,
 *   g = 0, dg/dt = 0, d2g/dt2 = 0 (the active constraints),
 *
 * (ImplicitStepSystem: how it is solved is the constrained linear algebra's
 * business) once per trial of the active-set iteration: a trial's gaps and
 * forces decide (ActiveSetIteration).
 *
 * Compliant constraints (Constraint::is_compliant) are implicit forces at
 * t_{n+1}: an engaged one adds its lambda and the law lambda/k + g +
 * (d/k) dg/dt = 0; a disengaged one has lambda = 0. The engaged set starts
 * from the previous step's and is iterated with the active set: engaged at
 * t_{n+1} iff g < 0 and -k g - d dg/dt > 0 there.
 *
 * Impacts (Sec. 5.3, restitution 0). A constraint that closes in a step is
 * left out of it; at t_{n+1} the positions and velocities are projected onto
 * g = dg/dt = 0 of the holding constraints (ImpactProjection), which gives
 * the impulse [N s] (DynamicState::impulse). Since the BDF-2 history would
 * span the jump, the step after an impact is the Richardson start again,
 * from the state after it.
 */
class Bdf2Integrator : public TimeIntegrator
{
public:
  /// Makes the step system of weight c (ImplicitStepSystem); the bool: its
  /// steps follow each other (make_implicit_step_system()).
  using StepSystemFactory =
      std::function<std::unique_ptr<ImplicitStepSystem>(double c, bool)>;

  /// Its entry in registered_integrators().
  static IntegratorEntry registry_entry();

  Bdf2Integrator(const SemiDiscreteSystem& system, double time_step,
                 unsigned int max_active_set_iterations,
                 LinearSolverType linear_solver = LinearSolverType::banded,
                 LinearAlgebra algebra = LinearAlgebra::fast);
  /// With the step systems of @p make_step_system (the tests' variants).
  Bdf2Integrator(const SemiDiscreteSystem& system, double time_step,
                 unsigned int max_active_set_iterations, LinearSolverType linear_solver,
                 LinearAlgebra algebra, StepSystemFactory make_step_system);
  ~Bdf2Integrator() override;

  std::string name() const override { return "bdf2"; }
  void initialize(const DynamicState& initial) override;
  void advance() override;
  const DynamicState& latest() const override { return current; }
  double time() const override { return current.t; }
  /// x_n, x_{n-1} (with J_n), the step number (the Richardson start is step 0) and
  /// the counters.
  void save(CheckpointOut& archive) const override;
  void load(CheckpointIn& archive) override;

private:
  /**
   * One implicit step of @p A from the history @p rho_q, @p rho_v to t1,
   * with the active-set iteration of Sec. 5.3 from @p active_at_start, and
   * the impact's projection if a constraint closed (into @p storage's
   * vectors, if it has them). @p held: the constraints that held at every
   * history point of a BDF-2 step (ImplicitStepSystem::start()); @p next:
   * the next step's history to form with the solution.
   */
  DynamicState implicit_step(ImplicitStepSystem& A, const dealii::Vector<double>& rho_q,
                             const dealii::Vector<double>& rho_v, double t1,
                             const std::vector<bool>& active_at_start,
                             const std::vector<bool>* held = nullptr,
                             const ImplicitStepSystem::NextHistory* next = nullptr,
                             DynamicState storage = {});
  /// What each constraint does in the current trial of the active-set iteration.
  const std::vector<ImplicitStepSystem::Role>& roles();
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
  /// The BDF-2 step x_{n+1} from x_n and x_{n-1}.
  void bdf2_step();
  /**
   * Sec. 5.3's test of a step's result @p x: every active rigid unilateral
   * constraint has lambda_i >= 0, every inactive one g_i(t, q) >= 0 (rows at
   * x.t).
   */
  bool satisfies_unilateral_constraints(const DynamicState& x);

  double dt;
  StepSystemFactory make_step_system;
  ConstraintEvaluator at_next;
  ActiveSetIteration active_set;
  std::unique_ptr<ConstrainedOperator> M; ///< of the impacts' projections
  ImpactProjection impacts;
  /// c = 3/(2 dt) of BDF-2; c = 1/dt, 2/dt of the start (made at first use).
  std::unique_ptr<ImplicitStepSystem> bdf2, start_full, start_half;
  /// The last step had an impact: the next one is a Richardson start.
  bool restart = false;
  DynamicState previous, current;
  DynamicState spare; ///< x_{n-2}: its vectors' memory for the next step
  /// rho_q, rho_v of the BDF-2 step; history_ready: the last step formed
  /// them (false after a start, an impact or a checkpoint's load).
  dealii::Vector<double> rho_q, rho_v;
  bool history_ready = false;
  unsigned long step_number = 0;
  std::vector<ImplicitStepSystem::Role> role; ///< workspace of roles()
  std::vector<double> gaps, rates;            ///< workspace of implicit_step()
  std::vector<bool> held;                     ///< workspace of bdf2_step()
};
} // namespace pantocat
