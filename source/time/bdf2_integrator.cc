#include <pantocat/time/bdf2_integrator.h>
#include <pantocat/time/dynamic_state_serialization.h>

#include <algorithm>

namespace pantocat
{
namespace
{
/// a fa + b fb entry by entry; an empty vector counts as zeros.
std::vector<double> combined_impulses(const std::vector<double>& a, const double fa,
                                      const std::vector<double>& b, const double fb)
{
  if (a.empty() && b.empty())
    return {};
  std::vector<double> sum(std::max(a.size(), b.size()), 0.);
  for (unsigned int i = 0; i < a.size(); ++i)
    sum[i] += fa * a[i];
  for (unsigned int i = 0; i < b.size(); ++i)
    sum[i] += fb * b[i];
  return sum;
}
} // namespace

Bdf2Integrator::Bdf2Integrator(const SemiDiscreteSystem& system, const double time_step,
                               const unsigned int max_iterations,
                               const LinearSolverType linear_solver,
                               const LinearAlgebra algebra)
    : Bdf2Integrator(
          system, time_step, max_iterations, linear_solver, algebra,
          [&system, linear_solver, algebra](const double c, const bool steps)
          { return make_implicit_step_system(system, c, algebra, linear_solver, steps); })
{
}

Bdf2Integrator::Bdf2Integrator(const SemiDiscreteSystem& system, const double time_step,
                               const unsigned int max_iterations,
                               const LinearSolverType linear_solver,
                               const LinearAlgebra algebra,
                               StepSystemFactory make_step_system)
    : TimeIntegrator(system), dt(time_step),
      make_step_system(std::move(make_step_system)), at_next(system),
      active_set(system, max_iterations),
      M(make_mass_operator(system, algebra, linear_solver)), impacts(system, *M)
{
}

Bdf2Integrator::~Bdf2Integrator() = default;

const std::vector<ImplicitStepSystem::Role>& Bdf2Integrator::roles()
{
  using Role = ImplicitStepSystem::Role;
  role.assign(system.n_constraints(), Role::none);
  for (const unsigned int i : active_set.active_indices())
    role[i] = Role::touching;
  for (const unsigned int i : active_set.force_indices())
    role[i] = Role::force;
  for (const unsigned int i : active_set.engaged_indices())
    role[i] = Role::engaged;
  return role;
}

DynamicState Bdf2Integrator::implicit_step(
    ImplicitStepSystem& A, const dealii::Vector<double>& rho_q,
    const dealii::Vector<double>& rho_v, const double t1,
    const std::vector<bool>& active_at_start, const std::vector<bool>* held,
    const ImplicitStepSystem::NextHistory* next, DynamicState storage)
{
  const unsigned int m = system.n_constraints();
  const std::vector<ConstraintState>& rows = at_next.at(t1);
  A.start(rows, t1, rho_q, rho_v, held, next, next && history_ready);
  DynamicState x = std::move(storage); // its vectors' memory, if any
  x.t = t1;
  x.impulse.clear();
  gaps.resize(m);
  rates.resize(m);
  // Sec. 5.3: each trial's gaps and forces decide the next one's roles.
  active_set.start(active_at_start);
  for (;;)
  {
    A.solve(roles(), x.q, x.v, x.a, x.lambda);
    for (unsigned int k = 0; k < m; ++k)
    {
      // (only those accept() reads: an active rigid one's are not)
      gaps[k] = active_set.reads_gap(k) ? rows[k].position_residual(x.q) : 0.;
      rates[k] = active_set.reads_rate(k) ? rows[k].velocity_residual(x.q, x.v) : 0.;
    }
    if (active_set.accept(gaps, x.lambda, t1, step_number + 1, rates))
      break;
    ++stats.active_set_iterations;
  }
  stats.active_set_changes += active_set.changes_in_step();
  x.active = active_set.active();
  clamp_compliant_forces(system, x.lambda);
  // A constraint that closed in the step (taken without it): the impact at
  // t_{n+1}, by projection; P is its impulse.
  if (active_set.impact_in_step())
  {
    ImpactProjection::Result r =
        impacts.project(rows, active_set.holding_indices(), t1, x.lambda, dt, x.q, x.v);
    x.impulse.swap(r.impulse);
    for (const unsigned int i : r.separated)
      x.active[i] = false, x.lambda[i] = 0.;
  }
  return x;
}

void Bdf2Integrator::initialize(const DynamicState& initial)
{
  current = initial;
  current.impulse.clear();
  previous = DynamicState();
  step_number = 0;
  restart = false;
  history_ready = false;
}

void Bdf2Integrator::richardson_start()
{
  history_ready = false;
  // Backward Euler with dt, and twice with dt/2; extrapolate (2nd order), Sec. 5.2.
  const DynamicState x0 = current;
  if (!start_full) // kept: a restart after an impact uses them again
  {
    start_full = make_step_system(1. / dt, false);
    start_half = make_step_system(2. / dt, false);
  }
  dealii::Vector<double> rq(x0.q), rv(x0.v); // rho = x_n / dt of Euler's step
  rq *= 1. / dt;
  rv *= 1. / dt;
  const DynamicState coarse = implicit_step(*start_full, rq, rv, x0.t + dt, x0.active);
  const std::vector<unsigned int> coarse_forces = active_set.force_indices();
  rq.equ(2. / dt, x0.q);
  rv.equ(2. / dt, x0.v);
  const DynamicState mid = implicit_step(*start_half, rq, rv, x0.t + 0.5 * dt, x0.active);
  rq.equ(2. / dt, mid.q);
  rv.equ(2. / dt, mid.v);
  DynamicState fine = implicit_step(*start_half, rq, rv, x0.t + dt, mid.active);
  // The impulses of both half steps.
  fine.impulse = combined_impulses(mid.impulse, 1., fine.impulse, 1.);
  // Extrapolated where both results solve the same equations: the same
  // constraints hold, the same of them carry a force (a touching one has
  // lambda = 0), and an impact falls in the dt step iff in the first half.
  if (fine.active == coarse.active && active_set.force_indices() == coarse_forces &&
      mid.impulse.empty() == coarse.impulse.empty())
  {
    DynamicState x = fine;
    x.q.sadd(2., -1., coarse.q);
    x.v.sadd(2., -1., coarse.v);
    x.a.sadd(2., -1., coarse.a);
    for (unsigned int i = 0; i < x.lambda.size(); ++i)
      x.lambda[i] = 2. * x.lambda[i] - coarse.lambda[i];
    clamp_compliant_forces(system, x.lambda);
    x.impulse = combined_impulses(fine.impulse, 2., coarse.impulse, -1.);
    if (satisfies_unilateral_constraints(x))
      fine = std::move(x);
  }
  // Else the start keeps the dt/2 result, which the active-set iteration of
  // its two steps made consistent (Sec. 5.3).
  previous = x0;
  current = std::move(fine);
}

bool Bdf2Integrator::satisfies_unilateral_constraints(const DynamicState& x)
{
  const std::vector<ConstraintState>& rows = at_next.at(x.t);
  for (unsigned int i = 0; i < system.n_constraints(); ++i)
    if (system.constraints[i]->is_rigid_unilateral() &&
        (x.active[i] ? x.lambda[i] < 0. : rows[i].position_residual(x.q) < 0.))
      return false;
  return true;
}

void Bdf2Integrator::bdf2_step()
{
  if (!bdf2)
    bdf2 = make_step_system(1.5 / dt, true);
  // rho = (4 x_n - x_{n-1}) / (2 dt), unless the last step formed it
  if (!history_ready)
  {
    rho_q.reinit(system.n_dofs(), true);
    rho_v.reinit(system.n_dofs(), true);
    rho_q.equ(2. / dt, current.q);
    rho_q.add(-0.5 / dt, previous.q);
    rho_v.equ(2. / dt, current.v);
    rho_v.add(-0.5 / dt, previous.v);
  }
  const ImplicitStepSystem::NextHistory next{&current.q, &current.v, 2. / dt, -0.5 / dt};
  // The constraints that held at t_n and t_{n-1}. x_{n-1} made by the start
  // (the initial state, or the state after an impact) may hold its
  // constraints less tightly than a step does (the static solution to about
  // 1e-13 m): none is counted then.
  const bool history_from_steps = step_number > 1 && previous.impulse.empty();
  held.resize(system.n_constraints());
  for (unsigned int i = 0; i < held.size(); ++i)
    held[i] = current.active[i] && previous.active[i];
  DynamicState x =
      implicit_step(*bdf2, rho_q, rho_v, current.t + dt, current.active,
                    history_from_steps ? &held : nullptr, &next, std::move(spare));
  // After an impact the BDF-2 history (x_n, x_{n-1}) spans the jump of the
  // velocities: the next step starts afresh from the state after it.
  history_ready = x.impulse.empty();
  if (history_ready)
    bdf2->take_next_history(rho_q, rho_v);
  spare = std::move(previous);
  previous = std::move(current);
  current = std::move(x);
}

void Bdf2Integrator::advance()
{
  if (step_number == 0 || restart)
    richardson_start();
  else
    bdf2_step();
  // After an impact the BDF-2 history (x_n, x_{n-1}) spans the jump of the
  // velocities: start afresh from the state after it (Sec. 5.2's start).
  restart = !current.impulse.empty();
  ++step_number;
  ++stats.steps;
}

void Bdf2Integrator::save(CheckpointOut& archive) const
{
  archive << step_number << previous << current << restart;
  save_statistics(archive);
}

void Bdf2Integrator::load(CheckpointIn& archive)
{
  archive >> step_number >> previous >> current >> restart;
  history_ready = false;
  load_statistics(archive);
  check_loaded(previous, "x_{n-1}");
  check_loaded(current, "x_n");
  check_loaded_steps(step_number);
}

IntegratorEntry Bdf2Integrator::registry_entry()
{
  IntegratorEntry e;
  e.name = "bdf2";
  e.description =
      "two-step BDF on the stabilised index-2 formulation (38) with a Richardson start";
  e.explicit_step_limit = false;
  e.writes_checkpoints = true;
  e.locates_events = false;
  e.create = [](const SemiDiscreteSystem& system, const TimeIntegrationParameters& p)
  {
    return std::make_unique<Bdf2Integrator>(system, p.time_step,
                                            p.max_active_set_iterations, p.linear_solver);
  };
  e.create_with_linear_algebra = [](const SemiDiscreteSystem& system,
                                    const TimeIntegrationParameters& p,
                                    const LinearAlgebra algebra)
  {
    return std::make_unique<Bdf2Integrator>(
        system, p.time_step, p.max_active_set_iterations, p.linear_solver, algebra);
  };
  return e;
}
} // namespace pantocat
