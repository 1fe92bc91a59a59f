#include <pantocat/analysis/stability_limit.h>
#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>
#include <pantocat/pantograph/three_mass_pantograph.h>
#include <pantocat/pantograph/two_mass_pantograph.h>
#include <pantocat/scene/scene_builder.h>
#include <pantocat/simulation/checkpoint.h>
#include <pantocat/simulation/dynamic_simulation.h>
#include <pantocat/simulation/initial_state.h>
#include <pantocat/system/catenary_system_builder.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <sstream>

namespace pantocat
{
std::unique_ptr<PantographModel> create_pantograph(const SceneParameters& scene,
                                                   const PantographParameters& p)
{
  if (scene.pantograph == PantographType::two_mass)
    return std::make_unique<TwoMassPantograph>(p.two_mass);
  if (scene.pantograph == PantographType::three_mass)
    return std::make_unique<ThreeMassPantograph>(p.three_mass);
  return nullptr;
}

DynamicSimulation::DynamicSimulation(const ProgramParameters& p)
    : parameters(p), space(create_catenary_discretisation(p.catenary, p.discretisation)),
      pantograph(create_pantograph(p.scene, p.pantograph)),
      motion{p.pantograph.initial_position, p.pantograph.speed}
{
  BuiltScene built = build_scene(p.scene, p.catenary, *space, pantograph.get(), motion);
  catenary_only = std::move(built.catenary_only);
  coupled = std::move(built.system);
  effects = built.active_effects;
  left_out = built.inactive_effects;

  for (unsigned int i = 0; i < coupled.n_constraints(); ++i)
    layout_.constraint_names.push_back(coupled.constraints[i]->name());
  layout_.dropper_indices = built.dropper_indices;
  layout_.contact_index = built.contact_index;
  if (pantograph)
    layout_.pantograph_coordinates = pantograph->coordinate_names();
  layout_.probe_positions = p.output.probe_positions;
  layout_.energy = p.output.energy;
  for (const double x : p.output.probe_positions)
  {
    require(coupled.has_block("contact wire"), "Output/Probe positions", x,
            "probes measure the contact wire, which this scene holds rigid");
    require(x > 0. && x < p.catenary.span, "Output/Probe positions", x,
            "must lie inside (0, Span)");
    probe_rows.push_back(wire_point_row(*space, coupled, Wire::contact_wire, x));
  }

  initial = p.scene.initial_shape == InitialShape::static_equilibrium
                ? consistent_initial_state(
                      catenary_only, coupled, pantograph.get(), built.contact_index,
                      p.pantograph.initial_contact_force, p.pantograph.initial_offset)
                : shaped_initial_state(coupled, *space, p.scene);
}

DynamicSimulation::~DynamicSimulation() = default;

double DynamicSimulation::explicit_stability_limit() const
{
  if (stability_limit == 0.)
    stability_limit = 2. / largest_circular_frequency(coupled);
  return stability_limit;
}

void DynamicSimulation::check_step_size() const
{
  const auto& ti = parameters.time_integration;
  if (ti.integrator != IntegratorType::half_explicit)
    return;
  const double limit = explicit_stability_limit();
  if (ti.time_step <= limit)
    return;
  std::ostringstream message;
  message << "above the stability limit 2/omega_max = " << std::setprecision(3) << limit
          << " s of the half-explicit method for this grid ("
          << to_string(parameters.discretisation.method)
          << ", N+1 = " << parameters.discretisation.n_intervals << ")";
  if (!ti.force_step_size)
    throw InputError("Time integration/Time step = " + number_to_string(ti.time_step) +
                     ": " + message.str() +
                     "; choose a smaller step or set Force step size = true");
  if (!warned)
    std::cerr << "pantocat-fem: warning: time step " << ti.time_step << " s is "
              << message.str() << " (forced)\n";
  warned = true;
}

void DynamicSimulation::check_load_resolution() const
{
  const auto& d = parameters.discretisation;
  // It matters for the contact constraint, whose row moves with x_p; a
  // prescribed moving force on a coarse grid is merely less accurate.
  if (d.load_shape != LoadShape::smoothed_delta || !layout_.has_contact() ||
      !coupled.has_block("contact wire"))
    return;
  const double h = parameters.catenary.span / d.n_intervals;
  if (h < d.load_half_width)
    return;
  std::ostringstream m;
  m << "Discretisation/Number of intervals = " << d.n_intervals
    << ": the grid spacing h = " << h
    << " m is not below Load half-width = " << d.load_half_width
    << " m, so the smoothed load of the contact is not resolved; choose Number of "
       "intervals > "
    << parameters.catenary.span / d.load_half_width << " or a wider Load half-width";
  throw InputError(m.str());
}

TimePoint DynamicSimulation::time_point(const DynamicState& s) const
{
  TimePoint p;
  p.t = s.t;
  p.x_p = motion.position(s.t);
  p.lambda = s.lambda;
  p.active = s.active;
  const unsigned int m = coupled.n_constraints();
  p.gap.resize(m);
  ConstraintState rows;
  for (unsigned int i = 0; i < m; ++i)
  {
    coupled.constraints[i]->evaluate(s.t, rows, 1); // gap and dg/dt only
    p.gap[i] = rows.position_residual(s.q);
    if (s.active[i])
    {
      p.position_residual = std::max(p.position_residual, std::abs(p.gap[i]));
      p.velocity_residual =
          std::max(p.velocity_residual, std::abs(rows.velocity_residual(s.q, s.v)));
    }
  }
  if (pantograph)
  {
    const DofBlock& b = coupled.block("pantograph");
    for (unsigned int i = 0; i < b.size; ++i)
      p.pantograph.push_back(s.q(b.first + i));
  }
  for (const SparseRow& row : probe_rows)
    p.probes.push_back(row.dot(s.q));
  if (layout_.energy)
    p.energy = coupled.energy(s.q, s.v, s.t);
  return p;
}

namespace
{
/**
 * Stops a run that goes unstable: non-finite values, or a displacement (or
 * Hermite slope) beyond @p bound, the span of the catenary: no physical
 * state of a wire comes near that, while an unstable mode grows through it
 * within a few steps of exponential growth.
 */
void check_bounded(const DynamicState& s, const unsigned long step, const double bound)
{
  const double largest = s.q.linfty_norm();
  bool finite = std::isfinite(largest) && std::isfinite(s.v.linfty_norm());
  for (const double l : s.lambda)
    finite = finite && std::isfinite(l);
  std::ostringstream m;
  if (!finite)
    m << "unstable: non-finite positions, velocities or multipliers at t = " << s.t
      << " s (step " << step << ")";
  else if (largest > bound)
    m << "unstable: a displacement of " << largest << " m exceeds the span " << bound
      << " m at t = " << s.t << " s (step " << step << ")";
  else
    return;
  throw SimulationError(m.str());
}

/**
 * The guards of a run (RunGuard) with F_ref = max(F_0, |lambda_i(0)|), the
 * scene's static force (the pantograph's uplift force or the moving force)
 * and the initial constraint forces, and E_ref = (T_c + T_w) L / 2.
 */
RunGuard make_guard(const ProgramParameters& p, const SemiDiscreteSystem& system,
                    const DynamicState& initial)
{
  const SceneParameters& scene = p.scene;
  double reference_force = scene.pantograph == PantographType::three_mass
                               ? p.pantograph.three_mass.uplift_force
                           : scene.pantograph == PantographType::moving_force
                               ? std::abs(scene.moving_force)
                               : p.pantograph.two_mass.uplift_force;
  for (const double l : initial.lambda)
    reference_force = std::max(reference_force, std::abs(l));
  const auto& c = p.catenary;
  return RunGuard(p.guards, system, reference_force,
                  0.5 * (c.carrier.tension + c.contact_wire.tension) * c.span, initial);
}
} // namespace

DynamicSimulation::Result
DynamicSimulation::run(const std::vector<SimulationObserver*>& observers,
                       const CheckpointPlan& checkpoints)
{
  check_step_size();
  const auto& ti = parameters.time_integration;
  auto integrator = create_time_integrator(coupled, ti);
  Result result;
  result.end_time = parameters.pantograph.end_time();
  const auto n_steps =
      static_cast<unsigned long>(std::ceil(result.end_time / ti.time_step - 1e-9));

  // The guards watch each time point after the outputs have it: a run
  // stopped by them keeps its time series up to the failure.
  RunGuard guard = make_guard(parameters, coupled, initial);
  std::vector<SimulationObserver*> all = observers;
  all.push_back(&guard);
  const auto notify = [&](const DynamicState& s)
  {
    const TimePoint p = time_point(s);
    for (auto* o : all)
    {
      o->observe(p);
      o->observe_state(p, s);
    }
  };

  const auto start = std::chrono::steady_clock::now();
  integrator->initialize(initial);
  const bool lags = integrator->multipliers_lag_one_step();
  unsigned long first_step = 1;
  if (checkpoints.resume_from)
  {
    checkpoints.resume_from->restore(*integrator, layout_, all);
    first_step = checkpoints.resume_from->step() + 1;
  }
  else
  {
    for (auto* o : all)
      o->start(layout_);
    if (!lags)
      notify(initial);
  }
  for (unsigned long n = first_step; n <= n_steps; ++n)
  {
    integrator->advance();
    check_bounded(integrator->latest(), n, parameters.catenary.span);
    notify(integrator->latest());
    if (n == n_steps)
      break;
    if (checkpoints.writer && checkpoints.interval > 0 && n % checkpoints.interval == 0)
      checkpoints.writer->write(n, *integrator, all);
    if (n == checkpoints.stop_after_steps)
      throw SimulationError("stopped after step " + std::to_string(n) + " of " +
                            std::to_string(n_steps) +
                            " at t = " + number_to_string(integrator->time()) +
                            " s as asked (Checkpoint/Stop after steps)");
  }
  integrator->finish();
  if (lags)
    notify(integrator->latest());
  result.time_loop_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.integrator = integrator->statistics();
  result.final_state = integrator->latest();
  result.guards = guard.extremes();
  for (auto* o : observers)
    o->finish();
  return result;
}
} // namespace pantocat
