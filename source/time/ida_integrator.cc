#include <pantocat/base/input_error.h>
#include <pantocat/time/active_set.h>
#include <pantocat/time/ida_integrator.h>
#include <pantocat/time/ida_sundials.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace pantocat
{
IdaIntegrator::IdaIntegrator(const SemiDiscreteSystem& system, const double output_step,
                             const double relative_tolerance,
                             const double absolute_tolerance,
                             const IdaLinearSolver solver, const LinearAlgebra algebra,
                             const unsigned int maximum_order)
    : TimeIntegrator(system), dt(output_step), rtol(relative_tolerance),
      atol(absolute_tolerance), max_order(maximum_order), linear_solver(solver),
      n(system.n_dofs()), m(system.n_constraints()),
      M(make_mass_operator(system, algebra)), rows(system), load_scratch(system.n_dofs())
{
  stats.events_localised = true;
}

IdaIntegrator::~IdaIntegrator() = default;

std::vector<unsigned int> IdaIntegrator::held_rigid(const std::vector<bool>& set) const
{
  std::vector<unsigned int> held;
  for (unsigned int k = 0; k < m; ++k)
    if (set[k] && !system.constraints[k]->is_compliant())
      held.push_back(k);
  return held;
}

void IdaIntegrator::accelerations(const double t, const std::vector<ConstraintState>& c,
                                  const std::vector<bool>& set,
                                  const dealii::Vector<double>& q,
                                  const dealii::Vector<double>& v,
                                  dealii::Vector<double>& a, std::vector<double>& lambda)
{
  // M a = f - K q - D v + G^T lambda of the compliant constraints (engaged as
  // in the set: at a root the toggled branch, the sign of the crossing), then
  // the rigid ones' lambda on acceleration level:
  // G a + 2 G_t v + G_tt q + z_tt = 0.
  system.load_at(t, a);
  system.stiffness.vmult(load_scratch, q);
  a -= load_scratch;
  system.damping.vmult(load_scratch, v);
  a -= load_scratch;
  std::vector<double> forces(m, 0.);
  for (unsigned int k = 0; k < m; ++k)
    if (set[k] && system.constraints[k]->is_compliant())
    {
      forces[k] = system.constraints[k]->trial_force(c[k].position_residual(q),
                                                     c[k].velocity_residual(q, v));
      c[k].G.add_transpose_to(a, forces[k]);
    }
  M->apply_inverse(a);
  M->project(
      held_rigid(set),
      [&](unsigned int k)
      { return c[k].G.dot(a) + 2. * c[k].G_t.dot(v) + c[k].G_tt.dot(q) + c[k].z_tt; },
      a, lambda, "IDA event");
  for (unsigned int k = 0; k < m; ++k)
    if (system.constraints[k]->is_compliant())
      lambda[k] = forces[k];
}

void IdaIntegrator::make_consistent(const double t, std::vector<bool> set)
{
  double* y = N_VGetArrayPointer(sun->y);
  double* yp = N_VGetArrayPointer(sun->yp);
  const auto& c = rows.at(t, 2);
  M->set_rows(c, t);
  dealii::Vector<double> q(n), v(n), a(n);
  std::copy(y, y + n, q.begin());
  std::copy(y + n, y + 2 * n, v.begin());
  std::vector<double> lambda(m, 0.), position_correction, impulse;
  bool closes = false;
  for (unsigned int k = 0; k < m; ++k)
    closes =
        closes || (set[k] && !active[k] && system.constraints[k]->is_rigid_unilateral());
  if (closes && pending_impulse.empty())
    pending_impulse.assign(m, 0.);
  std::vector<double> event_impulse(m, 0.);
  for (unsigned int round = 0; round <= m; ++round)
  {
    // Positions and velocities onto g = dg/dt = 0 (an inelastic impact where a
    // constraint closes; round-off elsewhere). v += M^-1 G^T P: P is the
    // impulse [N s].
    const std::vector<unsigned int> held = held_rigid(set);
    M->project(
        held, [&](unsigned int k) { return c[k].position_residual(q); }, q,
        position_correction, "IDA event");
    M->project(
        held, [&](unsigned int k) { return c[k].velocity_residual(q, v); }, v, impulse,
        "IDA event");
    if (closes)
      for (const unsigned int k : held)
      {
        pending_impulse[k] += impulse[k];
        event_impulse[k] += impulse[k];
      }
    accelerations(t, c, set, q, v, a, lambda);
    // A constraint that pulls separates: g'' > 0 without it.
    bool released = false;
    for (const unsigned int k : held)
      if (lambda[k] < 0. && system.constraints[k]->is_unilateral())
        set[k] = false, released = true;
    if (!released)
      break;
  }
  record_events(t, set, closes, event_impulse);
  std::copy(q.begin(), q.end(), y);
  std::copy(v.begin(), v.end(), y + n);
  for (unsigned int k = 0; k < m; ++k)
    y[2 * n + k] = lambda[k], y[2 * n + m + k] = 0.;
  std::copy(v.begin(), v.end(), yp);
  std::copy(a.begin(), a.end(), yp + n);
  std::fill(yp + 2 * n, yp + 2 * n + 2 * m, 0.);
}

void IdaIntegrator::record_events(const double t, const std::vector<bool>& set,
                                  const bool closes,
                                  const std::vector<double>& event_impulse)
{
  for (unsigned int k = 0; k < m; ++k)
    if (set[k] != active[k])
    {
      stats.localised_events.push_back(
          {t, k, set[k], set[k] && closes ? event_impulse[k] : 0.});
      ++stats.active_set_changes;
    }
  active = set;
}

void IdaIntegrator::initialize(const DynamicState& initial)
{
  sun = std::make_unique<Sundials>(*this);
  active = initial.active;
  // The compliant constraints' branch and force from the initial state.
  std::vector<double> initial_lambda = initial.lambda;
  const auto& c0 = rows.at(initial.t, 1);
  for (unsigned int k = 0; k < m; ++k)
    if (system.constraints[k]->is_compliant())
    {
      const Constraint& law = *system.constraints[k];
      const double g = c0[k].position_residual(initial.q),
                   rate = c0[k].velocity_residual(initial.q, initial.v);
      initial_lambda[k] = law.compliant_force(g, rate);
      active[k] = !law.is_unilateral() || (g < 0. && law.trial_force(g, rate) > 0.);
    }
  double* y = N_VGetArrayPointer(sun->y);
  double* yp = N_VGetArrayPointer(sun->yp);
  std::copy(initial.q.begin(), initial.q.end(), y);
  std::copy(initial.v.begin(), initial.v.end(), y + n);
  for (unsigned int k = 0; k < m; ++k)
    y[2 * n + k] = initial_lambda[k], y[2 * n + m + k] = 0.;
  std::copy(initial.v.begin(), initial.v.end(), yp);
  std::copy(initial.a.begin(), initial.a.end(), yp + n);
  std::fill(yp + 2 * n, yp + 2 * n + 2 * m, 0.);
  // Absolute tolerances: atol on q [m] and v [m/s]; the multipliers are
  // excluded from the error test (IDASetSuppressAlg) but weigh in IDA's Newton
  // convergence test, where a tolerance of atol on forces of ~100 N (lambda)
  // and on the GGL multiplier mu (~0) makes the test fail for no reason:
  // 1e-6 of their scale (1 N) there.
  double* tol = N_VGetArrayPointer(sun->tolerances);
  for (unsigned int i = 0; i < 2 * n + 2 * m; ++i)
    tol[i] = i < 2 * n ? atol : 1e-6;
  void* mem = sun->memory;
  bool ok = IDAInit(mem, Sundials::residual, initial.t, sun->y, sun->yp) == IDA_SUCCESS &&
            IDASetUserData(mem, sun.get()) == IDA_SUCCESS &&
            IDASVtolerances(mem, rtol, sun->tolerances) == IDA_SUCCESS &&
            IDASetId(mem, sun->id) == IDA_SUCCESS &&
            IDASetSuppressAlg(mem, SUNTRUE) == IDA_SUCCESS &&
            IDASetLinearSolver(mem, sun->solver, sun->J) == IDA_SUCCESS &&
            IDASetJacFn(mem, Sundials::jacobian) == IDA_SUCCESS &&
            IDARootInit(mem, m, Sundials::roots) == IDA_SUCCESS &&
            IDASetMaxNumSteps(mem, max_steps_per_output_step) == IDA_SUCCESS &&
            IDASetMinStep(mem, min_step_per_output_step * dt) == IDA_SUCCESS &&
            IDASetMaxOrd(mem, static_cast<int>(max_order)) == IDA_SUCCESS &&
            IDASetErrHandlerFn(mem, keep_error_message, &sun->last_error) == IDA_SUCCESS;
  std::vector<int> direction(m, -1); // gaps and forces falling through zero
  // (A scene without constraints has no roots: IDA refuses directions then.)
  ok = ok && (m == 0 || IDASetRootDirection(mem, direction.data()) == IDA_SUCCESS);
  if (!ok)
    throw SimulationError("IDA: the solver could not be set up");
  current = initial;
  current.impulse.clear();
  pending_impulse.clear();
  stats.localised_events.clear();
  counted.clear();
}

void IdaIntegrator::read_state(const double t)
{
  const double* y = N_VGetArrayPointer(sun->y);
  const double* yp = N_VGetArrayPointer(sun->yp);
  current.t = t;
  current.q.reinit(n, true);
  current.v.reinit(n, true);
  current.a.reinit(n, true);
  std::copy(y, y + n, current.q.begin());
  std::copy(y + n, y + 2 * n, current.v.begin());
  std::copy(yp + n, yp + 2 * n, current.a.begin());
  current.lambda.assign(y + 2 * n, y + 2 * n + m);
  clamp_compliant_forces(system, current.lambda);
  current.active = active;
  // The impacts located since the last output point are reported with it.
  current.impulse.swap(pending_impulse);
  pending_impulse.clear();
}

void IdaIntegrator::restart(const double t)
{
  collect_counters();
  counted = stats.counters; // IDAReInit resets IDA's counters
  if (IDAReInit(sun->memory, t, sun->y, sun->yp) != IDA_SUCCESS)
    throw SimulationError("IDA: restart after an event failed");
}

void IdaIntegrator::release_pulling_constraints(const double t)
{
  const double* lambda = N_VGetArrayPointer(sun->y) + 2 * n;
  std::vector<bool> set = active;
  bool pulls = false;
  for (unsigned int k = 0; k < m; ++k)
    if (active[k] && system.constraints[k]->is_rigid_unilateral() && lambda[k] < 0.)
      set[k] = false, pulls = true;
  if (!pulls)
    return;
  make_consistent(t, set);
  restart(t);
}

void IdaIntegrator::advance()
{
  const double t_out = current.t + dt;
  double t = current.t;
  unsigned int events = 0;
  while (t < t_out - 1e-14 * std::max(1., std::abs(t_out)))
  {
    const int flag = IDASolve(sun->memory, t_out, &t, sun->y, sun->yp, IDA_NORMAL);
    if (flag == IDA_ROOT_RETURN)
    {
      if (++events > max_events_per_output_step)
      {
        std::ostringstream s;
        s << "IDA failed at t = " << t << " s: more than " << max_events_per_output_step
          << " switches of the active set in the output step from " << current.t
          << " s (the constraints chatter)";
        throw SimulationError(s.str());
      }
      std::vector<int> found(m, 0);
      IDAGetRootInfo(sun->memory, found.data());
      std::vector<bool> set = active;
      for (unsigned int k = 0; k < m; ++k)
        if (found[k] != 0)
          set[k] = !active[k];
      make_consistent(t, set);
      restart(t);
      continue;
    }
    if (flag < 0)
    {
      std::ostringstream s;
      s << "IDA failed at t = " << t
        << " s: " << ida_failure_reason(flag, min_step_per_output_step * dt);
      if (!sun->last_error.empty())
        s << "; IDA: " << sun->last_error;
      throw SimulationError(s.str());
    }
  }
  release_pulling_constraints(t_out);
  // The derivative at t_out (IDA returns y' with y).
  read_state(t_out);
  ++stats.steps;
  collect_counters();
}

void IdaIntegrator::collect_counters()
{
  long steps = 0, residuals = 0, jacobians = 0, error_failures = 0,
       nonlinear_failures = 0, setups = 0, roots = 0;
  IDAGetNumSteps(sun->memory, &steps);
  IDAGetNumResEvals(sun->memory, &residuals);
  IDAGetNumJacEvals(sun->memory, &jacobians);
  IDAGetNumErrTestFails(sun->memory, &error_failures);
  IDAGetNumNonlinSolvConvFails(sun->memory, &nonlinear_failures);
  IDAGetNumLinSolvSetups(sun->memory, &setups);
  IDAGetNumGEvals(sun->memory, &roots);
  stats.counters = {{"ida_steps", steps},
                    {"residual_evaluations", residuals},
                    {"jacobian_evaluations", jacobians},
                    {"error_test_failures", error_failures},
                    {"nonlinear_convergence_failures", nonlinear_failures},
                    {"linear_solver_setups", setups},
                    {"root_function_evaluations", roots}};
  for (std::size_t i = 0; i < counted.size(); ++i)
    stats.counters[i].second += counted[i].second;
}

IntegratorEntry IdaIntegrator::registry_entry()
{
  IntegratorEntry e;
  e.name = "ida";
  e.description = "SUNDIALS IDA (variable order and step) on the GGL index-2 system, "
                  "events located by root finding";
  e.explicit_step_limit = false;
  e.writes_checkpoints = false;
  e.locates_events = true;
  e.create_with_linear_algebra = [](const SemiDiscreteSystem& system,
                                    const TimeIntegrationParameters& p,
                                    const LinearAlgebra algebra)
  {
    return std::make_unique<IdaIntegrator>(
        system, p.time_step, p.ida_relative_tolerance, p.ida_absolute_tolerance,
        p.ida_linear_solver == "umfpack"        ? IdaLinearSolver::umfpack
        : p.ida_linear_solver == "trilinos-klu" ? IdaLinearSolver::trilinos_klu
                                                : IdaLinearSolver::sundials_klu,
        algebra, p.ida_maximum_order);
  };
  e.create = [make = e.create_with_linear_algebra](const SemiDiscreteSystem& system,
                                                   const TimeIntegrationParameters& p)
  { return make(system, p, LinearAlgebra::fast); };
  return e;
}
} // namespace pantocat
