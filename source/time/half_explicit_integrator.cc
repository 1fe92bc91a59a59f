#include <pantocat/base/input_error.h>
#include <pantocat/time/dynamic_state_serialization.h>
#include <pantocat/time/half_explicit_integrator.h>

#include <algorithm>
#include <cmath>

namespace pantocat
{
HalfExplicitIntegrator::HalfExplicitIntegrator(const SemiDiscreteSystem& system,
                                               const double time_step,
                                               const unsigned int max_iterations,
                                               const LinearAlgebra algebra)
    : HalfExplicitIntegrator(system,
                             make_half_explicit_step_system(system, time_step, algebra),
                             max_iterations, algebra)
{
}

HalfExplicitIntegrator::HalfExplicitIntegrator(
    const SemiDiscreteSystem& system, std::unique_ptr<HalfExplicitStepSystem> step_system,
    const unsigned int max_iterations, const LinearAlgebra algebra)
    : TimeIntegrator(system), dt(step_system->time_step()),
      levels(std::move(step_system)), at_n(system), at_half(system), at_next(system),
      active_set(system, max_iterations), M(make_mass_operator(system, algebra)),
      impacts(system, *M)
{
  const unsigned int n = system.n_dofs(), m = system.n_constraints();
  for (auto* x : {&q, &v, &v_prev, &a, &q_new, &v_new})
    x->reinit(n);
  lambda.assign(m, 0.);
  gaps.assign(m, 0.);
  for (unsigned int i = 0; i < m; ++i)
    if (system.constraints[i]->is_compliant())
      compliant.push_back(i);
}

void HalfExplicitIntegrator::set_time_step(const double time_step)
{
  dt = time_step;
  levels->set_time_step(dt);
  history_start = step_number;
}

void HalfExplicitIntegrator::initialize(const DynamicState& initial)
{
  t = initial.t;
  q = initial.q;
  v = initial.v;
  a = initial.a;
  // v_{-1} = v_0 - dt a_0.
  v_prev = initial.v;
  v_prev.add(-dt, initial.a);
  previous = &v_prev;
  active_now = initial.active;
  reported = initial;
  reported.impulse.clear();
  pending_impulse.clear();
  step_number = 0;
  history_start = 0;
}

void HalfExplicitIntegrator::set_previous_velocity(const dealii::Vector<double>& vp)
{
  v_prev = vp;
  previous = &v_prev;
  history_start = step_number;
}

void HalfExplicitIntegrator::compute_compliant_forces()
{
  const auto& sn = at_n.states();
  for (const unsigned int i : compliant)
  {
    // Explicit in the force: g and dg/dt at t_n from q_n and the velocity of
    // the damping forces of (39), (41), v_{n-1/2} = (v_{n-1} + v_n)/2.
    const ConstraintState& s = sn[i];
    const double gap = s.position_residual(q);
    const double rate = s.G_t.dot(q) + 0.5 * (s.G.dot(*previous) + s.G.dot(v)) + s.z_t;
    const Constraint& c = *system.constraints[i];
    lambda[i] = c.compliant_force(gap, rate);
    const bool engaged = !c.is_unilateral() || lambda[i] > 0.;
    stats.active_set_changes += engaged != active_now[i];
    active_now[i] = engaged;
  }
}

void HalfExplicitIntegrator::start_step()
{
  at_n.at(t);
  at_half.at(t + 0.5 * dt, 1); // (40) needs G and G_t at t_{n+1/2} and t_{n+1}
  at_next.at(t + dt, 1);
  compute_compliant_forces();
  HalfExplicitStepSystem::Step step;
  step.t = t;
  step.number = step_number;
  step.q = &q;
  step.v = &v;
  step.v_previous = previous;
  step.at_n = &at_n.states();
  step.at_half = &at_half.states();
  step.at_next = &at_next.states();
  // The history of the two-step update is the method's own since two steps
  // (no start, new v_{n-1} or impact at t_n): J_{n-1} and J_n held in it.
  if (step_number >= history_start + 2 && pending_impulse.empty())
  {
    step.active_before = &reported.active;
    step.active_now = &active_now;
  }
  step.a = &a;
  step.q_next = &q_new;
  step.v_next = &v_new;
  step.lambda = &lambda;
  step.gaps = &gaps;
  levels->start(step);
}

void HalfExplicitIntegrator::trial(const std::vector<unsigned int>& force_set,
                                   const std::vector<unsigned int>& active_set_of_step)
{
  // Step 1: (M + dt/2 D) a_n = f - K q_n - D (v_{n-1} + v_n)/2 + G^T lambda_n
  // with the smoothing (41), g^(II) = 0 at t_n on the constraints with a
  // force (the touching ones carry none); and the unconstrained part of (40),
  // v* = v_{n-1} + 2 dt a_n, q* = q_n + dt (v_n + v*)/2.
  levels->acceleration_level(force_set, &active_set_of_step);
  // Step 2, (40): q_{n+1} = q* + dt M^-1 ((dt G(t_n) + G_t(t_{n+1/2}))^T eta
  // + G(t_{n+1/2})^T mu), v_{n+1} = v* + 2 dt M^-1 G(t_n)^T eta with
  // g = dg/dt = 0 at t_{n+1} on the active set.
  levels->position_level(active_set_of_step);
}

void HalfExplicitIntegrator::advance()
{
  start_step();
  active_set.start(active_now);
  for (;;)
  {
    trial(active_set.force_indices(), active_set.active_indices());
    if (active_set.accept(gaps, lambda, t + dt, step_number + 1))
      break;
    ++stats.active_set_iterations;
  }
  levels->finish_step();
  stats.active_set_changes += active_set.changes_in_step();
  std::vector<double> impulse;
  std::vector<unsigned int> separated;
  const bool closed = active_set.impact_in_step();
  if (closed)
    impact(impulse, separated);
  move_on(closed, impulse, separated);
}

void HalfExplicitIntegrator::impact(std::vector<double>& impulse,
                                    std::vector<unsigned int>& separated)
{
  // A constraint that closed in this step (taken without it: it had no
  // contact at t_n, so no force lambda_n) is an impact at t_{n+1}: q_{n+1},
  // v_{n+1} are projected onto the holding constraints; P is the impulse.
  jump = v_new;
  ImpactProjection::Result r = impacts.project(
      at_next.states(), active_set.holding_indices(), t + dt, lambda, dt, q_new, v_new);
  impulse.swap(r.impulse);
  separated.swap(r.separated);
  jump.sadd(-1., 1., v_new); // v+ - v- = M^-1 G^T P
}

void HalfExplicitIntegrator::move_on(const bool impact, std::vector<double>& impulse,
                                     const std::vector<unsigned int>& separated)
{
  // Report t_n: q_n, v_n satisfy the constraints of J_n; lambda_n belongs to
  // the set J_{n+1} of this step (a constraint closing in this step already
  // carries its impact force). Then move on to t_{n+1}.
  reported.t = t;
  reported.q.swap(q); // q_n
  q.swap(q_new);      // q_{n+1}
  // v_n is both the reported velocity and v_{n-1} of the next step: one
  // vector, reported.v, without a copy.
  reported.v.swap(v); // v_n
  v.swap(v_new);      // v_{n+1}
  previous = &reported.v;
  if (impact)
  {
    // The two-step update (40) takes v_{n+2} from v_n: with the jump added
    // there as well, the impact is not forgotten at the next step (nor
    // undone when the constraint separates again). A restart from the state
    // after the impact (v_n := v_{n+1} - dt a_{n+1}) would do the same, but
    // its one-step map amplifies the stiffest modes by up to sqrt(3) when
    // impacts follow each other closely.
    v_prev = reported.v;
    v_prev += jump;
    previous = &v_prev;
  }
  reported.a.swap(a);
  reported.lambda = lambda;
  reported.active = active_now;
  reported.impulse.swap(pending_impulse); // the impact at t_n, if any
  pending_impulse.swap(impulse);
  active_now = active_set.active();
  for (const unsigned int i : compliant) // explicit: engaged at t_n, not iterated
    active_now[i] = reported.active[i];
  for (const unsigned int i : separated) // their impulse would pull: they separate
    active_now[i] = false;
  t += dt;
  ++step_number;
  ++stats.steps;
}

void HalfExplicitIntegrator::finish()
{
  // Step 1 alone at the final time: a_N and lambda_N with the current active
  // set, on acceleration level as in a step (Sec. 5.3): a rigid unilateral
  // constraint with lambda_N < 0 holds without force (it touches: g = dg/dt
  // = 0 at t_N come from the step that reached t_N), and step 1 is repeated.
  std::vector<unsigned int> A;
  for (unsigned int i = 0; i < active_now.size(); ++i)
    if (active_now[i] && !system.constraints[i]->is_compliant())
      A.push_back(i);
  for (;;)
  {
    start_step();
    levels->acceleration_level(A, nullptr);
    levels->finish_step();
    const auto pulls = [&](const unsigned int i)
    { return system.constraints[i]->is_unilateral() && lambda[i] < 0.; };
    const auto kept = std::remove_if(A.begin(), A.end(), pulls);
    if (kept == A.end())
      break;
    A.erase(kept, A.end());
  }
  if (previous == &reported.v) // v_{n-1} stays the integrator's own
  {
    v_prev = reported.v;
    previous = &v_prev;
  }
  reported.t = t;
  reported.q = q;
  reported.v = v;
  reported.a = a;
  reported.lambda = lambda;
  reported.active = active_now;
  reported.impulse = pending_impulse;
}

void HalfExplicitIntegrator::save(CheckpointOut& archive) const
{
  // a_n and lambda_n are recomputed from these in the next step (39).
  archive << t << step_number << q << v << *previous << active_now << reported
          << pending_impulse;
  save_statistics(archive);
}

void HalfExplicitIntegrator::load(CheckpointIn& archive)
{
  archive >> t >> step_number >> q >> v >> v_prev >> active_now >> reported >>
      pending_impulse;
  previous = &v_prev;
  load_statistics(archive);
  if (!std::isfinite(t))
    throw InputError("the time t_n is not finite");
  check_loaded(q, system.n_dofs(), "q_n");
  check_loaded(v, system.n_dofs(), "v_n");
  check_loaded(v_prev, system.n_dofs(), "v_{n-1}");
  check_loaded(active_now, "the active set");
  check_loaded(reported, "the last reported state");
  check_loaded_steps(step_number);
}

IntegratorEntry HalfExplicitIntegrator::registry_entry()
{
  IntegratorEntry e;
  e.name = "half-explicit";
  e.description = "the reversible half-explicit method (39)-(41) (explicit in the "
                  "unknowns, stable for dt < 2/omega_max)";
  e.explicit_step_limit = true;
  e.writes_checkpoints = true;
  e.locates_events = false;
  e.create_with_linear_algebra = [](const SemiDiscreteSystem& system,
                                    const TimeIntegrationParameters& p,
                                    const LinearAlgebra algebra)
  {
    return std::make_unique<HalfExplicitIntegrator>(system, p.time_step,
                                                    p.max_active_set_iterations, algebra);
  };
  e.create = [make = e.create_with_linear_algebra](const SemiDiscreteSystem& system,
                                                   const TimeIntegrationParameters& p)
  { return make(system, p, LinearAlgebra::fast); };
  return e;
}
} // namespace pantocat
