#include <pantocat/analysis/stability_limit.h>
#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>
#include <pantocat/lac/vector_bounds.h>
#include <pantocat/scene/scene_builder.h>
#include <pantocat/scene/steady_arms.h>
#include <pantocat/simulation/case_runner.h>
#include <pantocat/simulation/catenary_design.h>
#include <pantocat/simulation/checkpoint.h>
#include <pantocat/simulation/initial_state.h>
#include <pantocat/time/integrator_registry.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>

namespace pantocat
{
/// The built scene, kept out of the header: only the runner sees scene/.
struct CaseRunner::Scene
{
  BuiltScene built;
};

namespace
{
/// The layout of the outputs: constraint names, pantographs and their contacts.
SimulationLayout make_layout(const BuiltScene& built, const Measurements& measurements)
{
  SimulationLayout layout;
  for (const auto& c : built.system.constraints)
    layout.constraint_names.push_back(c->name());
  layout.dropper_indices = built.dropper_indices;
  unsigned int coordinate = 0;
  for (const ScenePantograph& p : built.pantographs)
  {
    PantographLayout l;
    l.name = p.block;
    l.column_suffix = p.column_suffix;
    l.model = p.data->model;
    l.contact = p.contact_index;
    l.wire_contacts = p.wire_contacts;
    l.initial_contact_force = p.data->parameters.initial_contact_force;
    l.static_force = p.model                     ? p.model->static_force()
                     : p.data->is_moving_force() ? std::abs(p.data->moving_force)
                                                 : 0.;
    if (p.model)
      l.coordinates = p.model->coordinate_names();
    l.first_coordinate = coordinate;
    coordinate += l.coordinates.size();
    layout.pantographs.push_back(l);
  }
  layout.probe_positions = measurements.probe_positions;
  layout.energy = measurements.energy;
  return layout;
}

/// The pantographs in contact at t = 0, for the consistent initial state.
std::vector<InitialContact> initial_contacts(const BuiltScene& built)
{
  std::vector<InitialContact> contacts;
  for (const ScenePantograph& p : built.pantographs)
    if (p.has_contact())
      contacts.push_back({p.model.get(), p.contact_index, p.block,
                          p.data->parameters.initial_contact_force,
                          p.data->parameters.initial_offset});
  return contacts;
}

/**
 * Run/Start = paper: (13) sets the frame's velocity from the head equation, so
 * a contact force that the head's spring does not carry at t = 0 becomes a
 * velocity of the frame relative to the head (lambda_p(0) / d_1 in the
 * two-mass model). The paper's data give 0.29 m/s; above 1 m/s a warning
 * names the start shock and the start without it.
 */
void warn_about_a_paper_start_shock(const BuiltScene& built, const DynamicState& s)
{
  constexpr double noticeable = 1.; // [m/s]
  for (const ScenePantograph& p : built.pantographs)
  {
    if (!p.has_contact())
      continue;
    const DofBlock& block = built.system.block(p.block);
    const SparseRow head = p.model->head_row();
    double head_speed = 0.;
    for (std::size_t k = 0; k < head.size(); ++k)
      head_speed += head.value[k] * s.v(block.first + head.index[k]);
    double relative = 0.;
    for (unsigned int i = 0; i < block.size; ++i)
      relative = std::max(relative, std::abs(s.v(block.first + i) - head_speed));
    if (relative > noticeable)
      std::cerr << "pantocat-fem: warning: Run/Start = paper starts " << p.block
                << "'s bodies at up to " << std::setprecision(3) << relative
                << " m/s relative to its head ((13) with "
                << p.data->parameters.subsection
                << "/Initial contact force = " << p.data->parameters.initial_contact_force
                << " N): a start shock; Run/Start = static equilibrium starts at rest\n";
  }
}

/**
 * Unreachable targets = release: names the droppers that the design left at
 * zero force because their targets needed a push.
 */
void warn_about_released_droppers(const CatenaryParameters& c,
                                  const std::vector<unsigned int>& released)
{
  if (released.empty())
    return;
  std::cerr << "pantocat-fem: warning: " << (c.name.empty() ? "the section" : c.name)
            << ": the target heights at " << released.size()
            << (released.size() == 1 ? " dropper" : " droppers") << " (x =";
  for (const unsigned int j : released)
    std::cerr << ' ' << c.start + c.dropper_positions[j];
  std::cerr << " m) need a push; those droppers hang at zero force in the static state "
               "and the contact wire passes above its targets there "
               "(Catenary/Droppers/Unreachable targets = release)\n";
}

/**
 * Stops a run that goes unstable: non-finite values, or a displacement (or
 * Hermite slope) beyond @p bound, the length of the domain: no physical state
 * of a wire comes near that, while an unstable mode grows through it within a
 * few steps of exponential growth.
 */
void check_bounded(const DynamicState& s, const unsigned long step, const double bound)
{
  bool all_finite = true;
  for (const double l : s.lambda)
    all_finite = all_finite && std::isfinite(l);
  if (all_finite && count_outside(s.q, bound) == 0 &&
      count_outside(s.v, std::numeric_limits<double>::max()) == 0)
    return; // the usual case; otherwise the message below says what is wrong
  const double largest = largest_magnitude(s.q);
  bool finite = std::isfinite(largest) && std::isfinite(largest_magnitude(s.v));
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
 * The initial state within the bound of check_bounded(): a static catenary
 * that sags by more than its length (loads far beyond what it carries, such
 * as an initial contact force of 1e308 N) is no result.
 */
void check_initial_bounded(const DynamicState& s, const double bound)
{
  const double largest = largest_magnitude(s.q);
  if (largest <= bound)
    return;
  std::ostringstream m;
  m << "initial state: ";
  if (std::isfinite(largest))
    m << "a displacement of " << largest << " m exceeds the span " << bound << " m";
  else
    m << "non-finite positions";
  m << " (are the loads at t = 0, e.g. Pantograph/Initial contact force, within what "
       "the catenary carries?)";
  throw SimulationError(m.str());
}
} // namespace

CaseRunner::CaseRunner(const Case& c, const Measurements& measurements)
    : data(c), asked_time_step(c.time_integration.time_step),
      scene(std::make_unique<Scene>())
{
  // The run ends exactly at t_e: the step is t_e / ceil(t_e / dt).
  data.time_integration.time_step = c.time_integration.step_for(c.end_time());
  design_sections();
  std::vector<SceneSection> line;
  for (unsigned int k = 0; k < sections_.size(); ++k)
    line.push_back({&sections_[k], spaces[k].get()});
  scene->built = build_scene(data.scene, line);
  const BuiltScene& built = scene->built;
  layout_ = make_layout(built, measurements);
  for (const double x : measurements.probe_positions)
  {
    require(!data.line.is_line(), "Output/Probe positions", x,
            "probes measure the contact wire of a single section; a line of " +
                std::to_string(data.line.n_sections) +
                " sections has two in each overlap; allowed: no probes on a line");
    require(built.system.has_block("contact wire"), "Output/Probe positions", x,
            "probes measure the contact wire, which this scene holds rigid");
    require(x > 0. && x < data.catenary.length(), "Output/Probe positions", x,
            "must lie inside (0, " + number_to_string(data.catenary.length()) +
                ") m, the wires' domain");
    probe_rows.push_back(
        wire_point_row(*spaces.front(), built.system, Wire::contact_wire, x));
  }
  require(data.scene.initial_shape == InitialShape::static_equilibrium ||
              !data.line.is_line(),
          "Scene/Initial shape", "not static equilibrium",
          "a prescribed initial shape is one section's; allowed on a line: static "
          "equilibrium");
  if (data.scene.initial_shape != InitialShape::static_equilibrium)
    initial = shaped_initial_state(built.system, *spaces.front(), data.scene);
  else if (data.scene.start == Start::paper)
  {
    initial = consistent_initial_state(built.catenary_only, built.system,
                                       initial_contacts(built));
    warn_about_a_paper_start_shock(built, initial);
  }
  else
    initial = static_initial_state(built.system, initial_contacts(built));
  for (PantographLayout& p : layout_.pantographs)
    if (p.has_contact())
      p.initial_contact_force = initial.lambda[p.contact];
  check_initial_bounded(initial, data.line_length());
}

UpliftPoints CaseRunner::uplift_points() const
{
  UpliftPoints points;
  if (!system().has_block(discretisation().wire_block_name(Wire::contact_wire)))
    return points; // a rigid wire: no uplift to measure
  for (unsigned int k = 0; k < sections_.size(); ++k)
  {
    const CatenaryParameters& c = sections_[k];
    if (data.scene.has_droppers())
      for (const double x : c.dropper_positions)
        points.droppers.push_back(
            wire_point_row(*spaces[k], system(), Wire::contact_wire, x));
    for (const double x : SteadyArms::positions(data.scene, c))
    {
      points.steady_arm_positions.push_back(c.start + x);
      points.steady_arms.push_back(
          wire_point_row(*spaces[k], system(), Wire::contact_wire, x));
    }
  }
  return points;
}

std::vector<double> CaseRunner::support_positions() const
{
  std::vector<double> x;
  for (const CatenaryParameters& c : sections_)
    for (const double s : c.support_positions())
      x.push_back(c.start + s);
  std::sort(x.begin(), x.end());
  // Shared supports of an overlap coincide to round-off of the sums of spans.
  x.erase(std::unique(x.begin(), x.end(),
                      [](const double a, const double b)
                      { return std::abs(a - b) < 1e-9; }),
          x.end());
  return x;
}

std::vector<double> CaseRunner::dropper_positions() const
{
  std::vector<double> x;
  for (const CatenaryParameters& c : sections_)
    for (const double d : c.dropper_positions)
      x.push_back(c.start + d);
  return x;
}

void CaseRunner::design_sections()
{
  sections_ = data.sections();
  for (CatenaryParameters& section : sections_)
  {
    spaces.push_back(create_catenary_discretisation(section, data.discretisation));
    if (!needs_design(data.scene, section))
      continue;
    CatenaryDesignResult d = design_catenary(data.scene, section, *spaces.back());
    section = d.catenary; // the grid is the same: only lengths and preloads change
    warn_about_released_droppers(section, d.released);
    if (!design_)
      design_ = std::move(d);
  }
  if (!data.line.is_line())
  {
    data.installation.apply(sections_.front()); // the catenary as installed
  }
  data.catenary = sections_.front();
}

CaseRunner::~CaseRunner() = default;

unsigned long CaseRunner::number_of_steps() const
{
  return data.time_integration.number_of_steps(data.end_time());
}

const SemiDiscreteSystem& CaseRunner::system() const
{
  return scene->built.system;
}

const std::vector<std::string>& CaseRunner::active_effects() const
{
  return scene->built.active_effects;
}

const std::vector<std::string>& CaseRunner::inactive_effects() const
{
  return scene->built.inactive_effects;
}

StaticEquilibrium CaseRunner::static_catenary() const
{
  // Loaded as the run starts: with lambda_p(0) of the paper's start, or with
  // the force of each pantograph in the static equilibrium of the whole system.
  std::vector<InitialContact> contacts = initial_contacts(scene->built);
  for (InitialContact& c : contacts)
    c.force = initial.lambda[c.constraint];
  return pantocat::static_catenary(scene->built.catenary_only, scene->built.system,
                                   contacts);
}

StaticElasticity
CaseRunner::static_elasticity(const ElasticityParameters& parameters) const
{
  return pantocat::static_elasticity(scene->built.catenary_only, *spaces.front(),
                                     scene->built.dropper_indices, parameters);
}

double CaseRunner::contact_wire_displacement(const dealii::Vector<double>& q,
                                             const double x) const
{
  return wire_point_row(*spaces.front(), system(), Wire::contact_wire, x).dot(q);
}

double CaseRunner::explicit_stability_limit() const
{
  if (stability_limit == 0.)
    stability_limit = 2. / largest_circular_frequency(system());
  return stability_limit;
}

void CaseRunner::check() const
{
  // The grid first: on an unresolved load the moving contact's map is
  // unstable at any step, and the grid is what to change.
  check_load_resolution();
  check_step_size();
}

std::string CaseRunner::step_size_problem() const
{
  if (step_size_checked)
    return step_size_reason;
  step_size_checked = true;
  const auto& ti = data.time_integration;
  if (!integrator_entry(ti.integrator).explicit_step_limit)
    return step_size_reason = "";
  const double limit = explicit_stability_limit();
  std::ostringstream message;
  message << std::setprecision(3);
  if (ti.time_step > limit)
  {
    message << "above the stability limit 2/omega_max = " << limit << " s of the "
            << ti.integrator << " method for this grid ("
            << to_string(data.discretisation.method)
            << ", N+1 = " << data.discretisation.n_intervals << ")"
            << compliant_stiffness_note(system());
    return step_size_reason = message.str();
  }
  if (const std::string damping = explicit_damping_problem(); !damping.empty())
    return step_size_reason = damping;
  // Below 2/omega_max: the moving contact's rows (doc/stability.md).
  if (!has_moving_constraints(system(), initial.active))
    return step_size_reason = "";
  StepLimitOptions options;
  options.steps = static_cast<unsigned int>(
      std::min<unsigned long>(options.steps, number_of_steps()));
  if (options.steps < 2 || half_explicit_step_allowed(system(), initial.active,
                                                      ti.time_step, initial.t, options))
    return step_size_reason = "";
  const HalfExplicitStepLimit l = half_explicit_step_limit(
      system(), initial.active, ti.time_step / options.margin, initial.t, options);
  if (l.critical == 0.)
    return step_size_reason = no_stable_step(l, options.steps);
  message << "exceeds the limit " << l.allowed << " s of the " << ti.integrator
          << " method with the moving contact: perturbations grow by a factor "
          << std::setprecision(5) << l.growth_unstable << std::setprecision(3)
          << " per step at dt = " << l.unstable << " s (the one-step map (39)-(41) over "
          << options.steps << " steps from x_p = " << initial_contact_position()
          << " m; 2/omega_max = " << limit << " s), stable up to " << l.critical
          << " s; allowed: dt <= " << options.margin << " x " << l.critical << " = "
          << l.allowed << " s";
  return step_size_reason = message.str();
}

std::string CaseRunner::explicit_damping_problem() const
{
  const ExplicitDampingLimit l = explicit_damping_limit(system(), initial.t);
  const double dt = data.time_integration.time_step;
  const double margin = StepLimitOptions().margin; // as for the moving contact
  if (!(dt > margin * l.step))
    return "";
  // The parameter: the penalty contact's Contact damping of its pantograph.
  std::string parameter =
      "the damping of '" + system().constraints[l.constraint]->name() + "'";
  for (unsigned int k = 0; k < layout_.pantographs.size(); ++k)
    if (std::count(layout_.pantographs[k].wire_contacts.begin(),
                   layout_.pantographs[k].wire_contacts.end(), l.constraint) > 0)
      parameter = data.scene.pantographs[k].contact_entry("Contact damping");
  std::ostringstream m;
  m << std::setprecision(3) << parameter << " = " << number_to_string(l.damping)
    << ": the " << data.time_integration.integrator
    << " method takes this damping force explicitly, stable only for dt c G M^-1 G^T "
       "<= 2 (G M^-1 G^T = "
    << l.mass_factor << " 1/kg); allowed at Time integration/Time step = " << dt
    << " s with the margin " << margin
    << ": 0 <= c <= " << margin * 2. / (dt * l.mass_factor)
    << " N s/m (or a step of at most " << margin * l.step
    << " s, or an implicit integrator: bdf2, generalized-alpha, ida)";
  damping_refusal = m.str();
  return "above the limit " + number_to_string(margin * l.step) +
         " s of the explicit damping of " + parameter + " = " +
         number_to_string(l.damping) + " N s/m";
}

std::string CaseRunner::no_stable_step(const HalfExplicitStepLimit& l,
                                       const unsigned int steps) const
{
  std::ostringstream m;
  m << std::setprecision(3) << "finds no stable step of the "
    << data.time_integration.integrator << " method with the moving contact down to "
    << l.unstable << " s: perturbations grow by ";
  if (std::isfinite(l.growth_unstable))
    m << "a factor " << l.growth_unstable << " per step there";
  else
    m << "more than the largest number per step there (the one-step map (39)-(41) "
         "overflows)";
  m << " over " << steps << " steps from x_p = " << initial_contact_position() << " m";
  for (const ScenePantograph& p : scene->built.pantographs)
    if (p.motion.acceleration(initial.t) > 0.)
      m << "; the pantograph accelerates at v_p / T_r = "
        << p.motion.acceleration(initial.t) << " m/s^2 (Speed ramp " << p.motion.ramp_time
        << " s)";
  m << compliant_stiffness_note(system());
  return m.str();
}

void CaseRunner::check_step_size() const
{
  const std::string problem = step_size_problem();
  if (problem.empty())
    return;
  if (!damping_refusal.empty())
    throw InputError(damping_refusal);
  if (!data.time_integration.force_step_size)
    throw InputError("Time integration/Time step = " + number_to_string(asked_time_step) +
                     ": " + problem +
                     "; choose a smaller step or set Force step size = true");
  if (!warned)
    std::cerr << "pantocat-fem: warning: time step " << asked_time_step << " s is "
              << problem << " (forced)\n";
  warned = true;
}

double CaseRunner::initial_contact_position() const
{
  for (const ScenePantograph& p : scene->built.pantographs)
    if (p.has_contact())
      return p.motion.position(initial.t);
  return std::numeric_limits<double>::quiet_NaN();
}

void CaseRunner::check_load_resolution() const
{
  const auto& d = data.discretisation;
  // It matters for a contact constraint, whose row moves with x_p; a
  // prescribed moving force on a coarse grid is merely less accurate.
  if (d.load_shape != LoadShape::smoothed_delta || !layout_.has_contact() ||
      !system().has_block(discretisation().wire_block_name(Wire::contact_wire)))
    return;
  const double h = data.catenary.length() / d.n_intervals;
  if (h < d.load_half_width)
    return;
  std::ostringstream m;
  m << "Discretisation/Number of intervals = " << d.n_intervals
    << ": the grid spacing h = " << h
    << " m is not below Load half-width = " << d.load_half_width
    << " m, so the smoothed load of the contact is not resolved; choose Number of "
       "intervals > "
    << data.catenary.length() / d.load_half_width << " or a wider Load half-width";
  throw InputError(m.str());
}

TimePoint CaseRunner::time_point(const DynamicState& s) const
{
  TimePoint p;
  TimePointWorkspace rows;
  fill_time_point(s, p, rows);
  return p;
}

void CaseRunner::fill_time_point(const DynamicState& s, TimePoint& p,
                                 TimePointWorkspace& workspace,
                                 const std::vector<ConstraintState>* known_rows) const
{
  const SemiDiscreteSystem& sys = system();
  p.t = s.t;
  p.x_p.clear();
  for (const ScenePantograph& pantograph : scene->built.pantographs)
    p.x_p.push_back(pantograph.motion.position(s.t));
  p.lambda = s.lambda;
  p.active = s.active;
  p.impulse = s.impulse;
  const unsigned int m = sys.n_constraints();
  p.gap.resize(m);
  p.position_residual = p.velocity_residual = 0.;
  // Constant rows (droppers, supports) are evaluated at the first time point
  // only, the moving ones at each unless the integrator's rows at s.t are known.
  const bool first = workspace.rows.size() != m;
  if (first)
  {
    workspace.rows.resize(m);
    workspace.time_dependent.resize(m);
    workspace.compliant.resize(m);
    workspace.unilateral.resize(m);
    for (unsigned int i = 0; i < m; ++i)
    {
      workspace.time_dependent[i] = sys.constraints[i]->depends_on_time();
      workspace.compliant[i] = sys.constraints[i]->is_compliant();
      workspace.unilateral[i] = sys.constraints[i]->is_unilateral();
    }
  }
  require_pushing_unilateral_forces(s, workspace.unilateral);
  for (unsigned int i = 0; i < m; ++i)
  {
    ConstraintState& own = workspace.rows[i];
    const bool moving = workspace.time_dependent[i];
    if (first || (moving && !known_rows))
      sys.constraints[i]->evaluate(s.t, own, 1); // gap and dg/dt only
    const ConstraintState& rows = moving && known_rows ? (*known_rows)[i] : own;
    p.gap[i] = rows.position_residual(s.q);
    if (s.active[i] && !workspace.compliant[i]) // springs deflect
    {
      p.position_residual = std::max(p.position_residual, std::abs(p.gap[i]));
      p.velocity_residual =
          std::max(p.velocity_residual, std::abs(rows.velocity_residual(s.q, s.v)));
    }
  }
  p.pantograph.clear();
  for (const ScenePantograph& pantograph : scene->built.pantographs)
    if (pantograph.model)
    {
      const DofBlock& b = sys.block(pantograph.block);
      for (unsigned int i = 0; i < b.size; ++i)
        p.pantograph.push_back(s.q(b.first + i));
    }
  p.probes.clear();
  for (const SparseRow& row : probe_rows)
    p.probes.push_back(row.dot(s.q));
  if (layout_.energy)
  {
    // The compact quadratic forms of the energy guard, not the matrices'.
    if (!workspace.energy)
      workspace.energy.emplace(sys);
    p.energy = (*workspace.energy)(s.q, s.v, s.t);
  }
}

void CaseRunner::require_pushing_unilateral_forces(
    const DynamicState& s, const std::vector<char>& unilateral) const
{
  for (unsigned int i = 0; i < unilateral.size(); ++i)
    if (unilateral[i] && s.lambda[i] < 0.)
    {
      std::ostringstream m;
      m << "internal error at t = " << number_to_string(s.t, 10)
        << " s: the force of the unilateral constraint " << layout_.constraint_names[i]
        << " is " << number_to_string(s.lambda[i], 6)
        << " N, but a unilateral constraint only pushes (lambda >= 0, Sec. 5.3): the "
           "integrator's step is inconsistent, and this time point is not written";
      throw SimulationError(m.str());
    }
}

RunGuard CaseRunner::make_guard() const
{
  // F_ref = max(F_0 of every pantograph, |lambda_i(0)|).
  double reference_force = 0.;
  for (const PantographLayout& p : layout_.pantographs)
    reference_force = std::max(reference_force, p.static_force);
  for (const double l : initial.lambda)
    reference_force = std::max(reference_force, std::abs(l));
  double tension_length = 0.; // sum of (T_c + T_w) L over the sections
  for (const CatenaryParameters& c : sections_)
    tension_length += (c.carrier.tension + c.contact_wire.tension) * c.length();
  return RunGuard(data.guards, system(), reference_force, 0.5 * tension_length, initial);
}

CaseRunner::Result CaseRunner::run(const std::vector<SimulationObserver*>& observers,
                                   const CheckpointPlan& checkpoints)
{
  check_step_size();
  const auto& ti = data.time_integration;
  auto integrator = create_time_integrator(system(), ti);
  Result result;
  result.end_time = data.end_time();
  const unsigned long n_steps = number_of_steps();

  // The guards watch each time point after the outputs have it: a run
  // stopped by them keeps its time series up to the failure.
  RunGuard guard = make_guard();
  std::vector<SimulationObserver*> all = observers;
  all.push_back(&guard);
  // One time point and one row workspace for the whole run: no allocations
  // per step.
  TimePoint p;
  TimePointWorkspace rows;
  const auto notify =
      [&](const DynamicState& s, const std::vector<ConstraintState>* known_rows)
  {
    fill_time_point(s, p, rows, known_rows);
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
      notify(initial, nullptr);
  }
  const double span_length = data.line_length(); // the bound of check_bounded()
  for (unsigned long n = first_step; n <= n_steps; ++n)
  {
    integrator->advance();
    // After the outputs, like the guards: the time series ends with the
    // time point that failed.
    notify(integrator->latest(), integrator->constraint_states_at_latest());
    check_bounded(integrator->latest(), n, span_length);
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
    notify(integrator->latest(), integrator->constraint_states_at_latest());
  result.time_loop_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.integrator = integrator->statistics();
  result.final_state = integrator->latest();
  result.guards = guard.extremes();
  result.stability_limit = integrator_entry(ti.integrator).explicit_step_limit
                               ? explicit_stability_limit()
                               : std::numeric_limits<double>::quiet_NaN();
  for (auto* o : observers)
    o->finish();
  return result;
}
} // namespace pantocat
