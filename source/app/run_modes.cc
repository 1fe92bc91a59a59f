#include <pantocat/analysis/eigenfrequency_analysis.h>
#include <pantocat/analysis/static_equilibrium.h>
#include <pantocat/app/run_modes.h>
#include <pantocat/base/input_error.h>
#include <pantocat/base/serialization.h>
#include <pantocat/io/json_writer.h>
#include <pantocat/io/plots.h>
#include <pantocat/io/progress_meter.h>
#include <pantocat/io/statistics_report.h>
#include <pantocat/io/time_series_writer.h>
#include <pantocat/io/vtu_time_series_writer.h>
#include <pantocat/io/wire_output.h>
#include <pantocat/scene/scene_builder.h>
#include <pantocat/simulation/checkpoint.h>
#include <pantocat/simulation/contact_statistics.h>
#include <pantocat/simulation/dynamic_simulation.h>
#include <pantocat/simulation/event_log.h>
#include <pantocat/simulation/moving_load_comparison.h>
#include <pantocat/simulation/run_statistics.h>

#include <deal.II/base/timer.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>

namespace pantocat
{
void run_eigenfrequencies(const ProgramParameters& p, std::ostream& out)
{
  std::vector<SubsystemFrequencies> rows;
  out << "Eigenfrequencies of the undamped wires, N+1 = " << p.discretisation.n_intervals
      << " (Table 1)\n"
      << std::left << std::setw(6) << "disc." << std::setw(14) << "subsystem"
      << std::right << std::setw(13) << "f_min [Hz]" << std::setw(13) << "f_max [Hz]"
      << std::setw(14) << "2/omega_max"
      << "    paper (N+1 = 500): f_min, f_max\n";
  for (const SpaceMethod method : p.eigenfrequency_discretisations)
  {
    DiscretisationParameters d = p.discretisation;
    d.method = method;
    const auto discretisation = create_catenary_discretisation(p.catenary, d);
    const auto frequencies = compute_extreme_frequencies(*discretisation);
    for (const auto& f : frequencies)
    {
      out << std::left << std::setw(6) << f.discretisation << std::setw(14) << f.subsystem
          << std::right << std::setprecision(5) << std::setw(13) << f.f_min_hz
          << std::setw(13) << f.f_max_hz << std::setw(14) << std::setprecision(2)
          << std::scientific << explicit_step_size_limit({f}) << std::defaultfloat
          << std::setprecision(5) << "    "
          << PaperTable1::f_min(f.discretisation, f.subsystem) << ", "
          << PaperTable1::f_max(f.discretisation, f.subsystem) << '\n';
      rows.push_back(f);
    }
    out << "  step-size limit of the half-explicit method, 2/omega_max ("
        << to_string(method) << "): " << std::setprecision(3)
        << explicit_step_size_limit(frequencies)
        << " s  (paper: " << (method == SpaceMethod::fdm ? "6.6e-05" : "5.3e-06")
        << " s)\n";
  }
  std::ofstream csv(p.output.directory + "/eigenfrequencies.csv");
  csv << "discretisation,subsystem,f_min_hz,f_max_hz\n" << std::setprecision(10);
  for (const auto& f : rows)
    csv << f.discretisation << ',' << f.subsystem << ',' << f.f_min_hz << ','
        << f.f_max_hz << '\n';
  if (!csv)
    throw SimulationError("cannot write " + p.output.directory + "/eigenfrequencies.csv");
}

void run_static_equilibrium(const ProgramParameters& p, std::ostream& out)
{
  require(p.scene.contact_wire == WireModel::elastic, "Scene/Contact wire", "rigid",
          "Mode = static computes the elastic catenary at rest: allowed elastic");
  const auto d = create_catenary_discretisation(p.catenary, p.discretisation);
  // The catenary of the scene (its pantograph's effects left out).
  const auto pantograph = create_pantograph(p.scene, p.pantograph);
  const BuiltScene scene =
      build_scene(p.scene, p.catenary, *d, pantograph.get(),
                  {p.pantograph.initial_position, p.pantograph.speed});
  const SemiDiscreteSystem& system = scene.catenary_only;

  // The contact load lambda_p(0) F_w(0)^T at x_p(0), (25) and (33), or the
  // scene's moving force there.
  const double force = p.scene.has_pantograph_body() ? p.pantograph.initial_contact_force
                       : p.scene.pantograph == PantographType::moving_force
                           ? p.scene.moving_force
                           : 0.;
  dealii::Vector<double> contact_load(system.n_dofs());
  SparseRow F;
  d->load_row(p.pantograph.initial_position, 0, F);
  F.shift(system.block("contact wire").first);
  F.add_transpose_to(contact_load, force);

  const StaticEquilibrium s = solve_static_equilibrium(system, contact_load);

  const std::string& dir = p.output.directory;
  write_wire_profiles(*d, system, s.q, dir + "/static_profile.csv",
                      dir + "/static_profile.vtu", p.output.vtu_subdivisions);
  std::ofstream csv(dir + "/dropper_forces.csv");
  csv << "dropper,x_m,force_n,gap_m,active\n" << std::setprecision(12);
  out << "Static equilibrium (" << to_string(d->method())
      << ", N+1 = " << d->n_intervals() << ", " << system.n_dofs() << " unknowns, "
      << system.n_constraints() << " dropper constraints)\n"
      << "  contact load " << force << " N at x_p = " << p.pantograph.initial_position
      << " m; contact wire there: " << std::setprecision(6) << F.dot(s.q)
      << " m (delta_eps-weighted)\n";
  for (unsigned int j = 0; j < system.n_constraints(); ++j)
  {
    csv << j + 1 << ',' << p.catenary.dropper_positions[j] << ',' << s.multipliers[j]
        << ',' << s.gaps[j] << ',' << (s.active[j] ? 1 : 0) << '\n';
    out << "  " << system.constraints[j]->name()
        << " at x = " << p.catenary.dropper_positions[j] << " m: force "
        << std::setprecision(6) << s.multipliers[j] << " N"
        << (s.active[j] ? "" : " (slack)") << '\n';
  }
  if (!csv)
    throw SimulationError("cannot write " + dir + "/dropper_forces.csv");
  out << "  wrote static_profile.csv, static_profile.vtu, dropper_forces.csv to " << dir
      << '\n';
}

namespace
{
/// The energy's range over the reported time points (Output/Energy).
struct EnergyRange : SimulationObserver
{
  void observe(const TimePoint& point) override
  {
    if (count++ == 0)
      initial = min = max = point.energy;
    min = std::min(min, point.energy);
    max = std::max(max, point.energy);
    final = point.energy;
  }
  void save(CheckpointOut& archive) const override
  {
    archive << count << initial << min << max << final;
  }
  void resume(const SimulationLayout&, CheckpointIn& archive) override
  {
    archive >> count >> initial >> min >> max >> final;
  }
  /// max |E(t) - E(0)| / |E(0)|.
  double relative_variation() const
  {
    return std::max(max - initial, initial - min) / std::abs(initial);
  }
  unsigned long count = 0;
  double initial = 0., min = 0., max = 0., final = 0.;
};

void write_summary(const std::string& file, const ProgramParameters& p,
                   const DynamicSimulation& simulation,
                   const DynamicSimulation::Result& r, const RunStatistics& stats,
                   const EventLog& events, const ContactForceStatistics* contact,
                   const EnergyRange& energy, const MovingLoadComparison* series)
{
  std::ofstream out(file);
  JsonWriter json(out);
  json.begin_object()
      .value("status", "completed")
      .value("discretisation", to_string(p.discretisation.method))
      .value("number_of_intervals",
             static_cast<unsigned long>(p.discretisation.n_intervals))
      .value("integrator", to_string(p.time_integration.integrator))
      .value("time_step", p.time_integration.time_step)
      .value("speed", p.pantograph.speed)
      .value("end_time", r.end_time)
      .value("unknowns", static_cast<unsigned long>(simulation.system().n_dofs()))
      .value("constraints",
             static_cast<unsigned long>(simulation.system().n_constraints()));
  json.begin_array("scene");
  for (const std::string& effect : simulation.active_effects())
    json.value("", effect);
  json.end_array();
  if (contact != nullptr)
  {
    json.begin_object("contact_force")
        .value("max", stats.contact_force_max())
        .value("min", stats.contact_force_min())
        .value("mean", stats.contact_force_mean())
        .value("std", stats.contact_force_std())
        .end_object();
    write_statistics(json, *contact);
  }
  if (energy.count > 0)
    json.begin_object("energy")
        .value("initial", energy.initial)
        .value("min", energy.min)
        .value("max", energy.max)
        .value("final", energy.final)
        .value("max_relative_variation", energy.relative_variation())
        .end_object();
  if (series != nullptr)
  {
    json.begin_array("series_reference");
    for (const auto& probe : series->probes())
      json.begin_object()
          .value("x", probe.x)
          .value("max_error", probe.max_error)
          .value("max_reference", probe.max_reference)
          .value("relative_error", probe.relative())
          .end_object();
    json.end_array();
  }
  json.begin_array("dropper_slack_intervals");
  for (const auto& list : stats.dropper_slack_intervals())
    json.intervals("", list);
  json.end_array();
  if (simulation.layout().has_contact())
    json.intervals("contact_loss_intervals", stats.contact_loss_intervals());
  json.value("max_droppers_slack_at_once",
             static_cast<unsigned long>(stats.max_droppers_slack_at_once()));
  // Events: located in time by the integrator (IDA's root finding), or at
  // step resolution from the reported time points.
  const auto& layout = simulation.layout();
  json.value("event_resolution", r.integrator.events_localised ? "localised" : "step");
  json.begin_array("events");
  auto event = [&](double t, const std::string& constraint, const std::string& kind)
  {
    json.begin_object()
        .value("t", t)
        .value("constraint", constraint)
        .value("kind", kind)
        .end_object();
  };
  if (r.integrator.events_localised)
    for (const SwitchEvent& e : r.integrator.localised_events)
    {
      const bool contact = e.constraint == layout.contact_index;
      event(e.t, layout.constraint_names[e.constraint],
            contact ? (e.closes ? "contact_return" : "contact_loss")
                    : (e.closes ? "dropper_taut" : "dropper_slack"));
    }
  else
    for (const ConstraintEvent& e : events.events())
      event(e.t, e.constraint, e.kind);
  json.end_array();
  if (!r.integrator.counters.empty())
  {
    json.begin_object("integrator_counters");
    for (const auto& [name, value] : r.integrator.counters)
      json.value(name, static_cast<unsigned long>(value));
    json.end_object();
  }
  json.value("steps", r.integrator.steps)
      .value("active_set_changes", r.integrator.active_set_changes)
      .value("active_set_iterations", r.integrator.active_set_iterations);
  json.begin_object("max_constraint_residual")
      .value("position", stats.max_position_residual())
      .value("velocity", stats.max_velocity_residual())
      .end_object();
  const GuardExtremes& g = r.guards;
  json.begin_object("guards")
      .value("max_drift", g.max_drift)
      .value("max_multiplier", g.max_multiplier)
      .value("reference_force", g.reference_force)
      .value("max_energy_increase", g.max_energy_increase)
      .value("min_energy_increase", g.min_energy_increase)
      .value("reference_energy", g.reference_energy)
      .end_object();
  json.value("stability_limit_explicit", r.stability_limit)
      .value("time_loop_seconds", r.time_loop_seconds)
      .end_object();
  if (!out)
    throw SimulationError("cannot write " + file);
}

std::string format_intervals(const std::vector<Interval>& list)
{
  if (list.empty())
    return "none";
  std::ostringstream s;
  s << std::setprecision(4);
  for (std::size_t i = 0; i < list.size(); ++i)
    s << (i ? ", " : "") << '[' << list[i].first << ", " << list[i].second << ']';
  return s.str();
}

/// Every file of the output directory with its size, sorted (detailed verbosity).
void list_files(std::ostream& out, const std::string& dir)
{
  std::vector<std::pair<std::string, std::uintmax_t>> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir))
    if (entry.is_regular_file())
      files.emplace_back(std::filesystem::relative(entry.path(), dir).string(),
                         entry.file_size());
  std::sort(files.begin(), files.end());
  out << "  files in " << dir << ":\n";
  for (const auto& [name, size] : files)
    out << "    " << name << " (" << size << " bytes)\n";
}
} // namespace

MovingLoadSeries moving_load_series(const ProgramParameters& p)
{
  WireParameters wire = p.catenary.contact_wire;
  if (!p.scene.contact_wire_tension)
    wire.tension = 0.;
  if (!p.scene.contact_wire_bending)
    wire.bending_stiffness = 0.;
  std::optional<SmoothedDelta> delta;
  if (p.discretisation.load_shape == LoadShape::smoothed_delta)
    delta.emplace(p.discretisation.load_half_width);
  return MovingLoadSeries(wire, p.catenary.span, p.scene.moving_force,
                          {p.pantograph.initial_position, p.pantograph.speed}, delta);
}

namespace
{
/// Which effects the scene assembles, which it leaves out, and the problem size.
void print_scene(std::ostream& out, const DynamicSimulation& simulation)
{
  const SemiDiscreteSystem& system = simulation.system();
  const SimulationLayout& layout = simulation.layout();
  out << "  scene: " << simulation.active_effects().size() << " effects\n";
  for (const std::string& effect : simulation.active_effects())
    out << "    " << effect << '\n';
  if (!simulation.inactive_effects().empty())
  {
    out << "  left out (not assembled):";
    for (const std::string& name : simulation.inactive_effects())
      out << (name == simulation.inactive_effects().front() ? " " : ", ") << name;
    out << '\n';
  }
  out << "  problem size: " << system.n_dofs() << " unknowns (";
  for (const DofBlock& b : system.blocks)
    out << (&b == &system.blocks.front() ? "" : ", ") << b.name << ' ' << b.size;
  out << "), " << system.n_constraints() << " constraints ("
      << layout.dropper_indices.size() << " droppers"
      << (layout.has_contact() ? ", contact" : "") << ")\n";
}
} // namespace

void run_dynamics(const ProgramParameters& p, std::ostream& out)
{
  dealii::TimerOutput timer(out, dealii::TimerOutput::never,
                            dealii::TimerOutput::wall_times);
  timer.enter_subsection("setup (assembly, initial state)");
  DynamicSimulation simulation(p);
  simulation.check_step_size(); // before any output is written
  simulation.check_load_resolution();
  const std::string& dir = p.output.directory;
  // A checkpoint to continue from is checked (its parameters) before any
  // output is touched; a fresh run removes a checkpoint of an earlier one.
  const std::string checkpoint_file = dir + "/checkpoint.bin";
  std::optional<CheckpointReader> resume_from;
  if (p.checkpoint.resume)
    resume_from.emplace(checkpoint_file, p.fingerprint);
  else
    std::filesystem::remove(checkpoint_file);
  // The results of an earlier run in this directory go before this one
  // starts: a run that fails or is killed must not leave them looking like
  // its own. (A resumed run keeps the stopped run's summary.json, "failed",
  // until it completes.)
  for (const char* name :
       {"contact_force.csv", "contact_force.png", "dropper_forces.png", "pantograph.png",
        "contact_force_statistics.png", "time_series.gp", "contact_force_statistics.gp"})
    std::filesystem::remove(dir + "/" + name);
  if (!resume_from)
    std::filesystem::remove(dir + "/summary.json");
  const CheckpointWriter checkpoint_writer(checkpoint_file, p.fingerprint);
  timer.leave_subsection();
  out << "Dynamic run: " << to_string(p.discretisation.method)
      << ", N+1 = " << p.discretisation.n_intervals << ", "
      << to_string(p.time_integration.integrator)
      << ", dt = " << p.time_integration.time_step << " s, v_p = " << p.pantograph.speed
      << " m/s, x_p from " << p.pantograph.initial_position << " to "
      << p.pantograph.final_position << " m\n";
  print_scene(out, simulation);
  if (resume_from)
    out << "  resuming from " << checkpoint_file << " after step " << resume_from->step()
        << '\n';

  TimeSeriesWriter series(dir + "/time_series.csv", p.output.time_series_interval);
  RunStatistics stats;
  EventLog events;
  const bool has_contact = simulation.layout().has_contact();
  struct FirstPoint : SimulationObserver
  {
    void start(const SimulationLayout& layout) override
    {
      contact = layout.contact_index;
    }
    void observe(const TimePoint& point) override
    {
      if (!seen)
        t = point.t, lambda_p = point.lambda[contact], seen = true;
    }
    void save(CheckpointOut& archive) const override { archive << seen << t << lambda_p; }
    void resume(const SimulationLayout& layout, CheckpointIn& archive) override
    {
      contact = layout.contact_index;
      archive >> seen >> t >> lambda_p;
    }
    unsigned int contact = 0;
    bool seen = false;
    double t = 0., lambda_p = 0.;
  } first;
  EnergyRange energy;
  std::vector<SimulationObserver*> observers{&series, &stats, &events};
  // Observers that are not asked for are not attached: they cost nothing.
  std::optional<ContactStatistics> contact;
  if (has_contact)
  {
    observers.push_back(&first);
    observers.push_back(
        &contact.emplace(p.statistics, simulation.discretisation(), simulation.system()));
  }
  if (p.output.energy)
    observers.push_back(&energy);
  std::optional<MovingLoadComparison> reference;
  if (p.scene.is_classical_moving_load() && !p.output.probe_positions.empty())
    observers.push_back(&reference.emplace(moving_load_series(p)));
  std::optional<VtuTimeSeriesWriter> vtu;
  if (p.output.vtu_interval > 0.)
    observers.push_back(
        &vtu.emplace(dir, p.output.vtu_interval, p.time_integration.time_step,
                     p.output.vtu_subdivisions, simulation.discretisation(),
                     simulation.system(), &timer));
  std::optional<ProgressMeter> progress;
  if (p.output.verbosity != Verbosity::quiet && stderr_is_terminal())
    observers.push_back(&progress.emplace(std::cerr, p.pantograph.end_time()));
  DynamicSimulation::Result r;
  try
  {
    const dealii::TimerOutput::Scope scope(timer, "time loop (includes the VTU frames)");
    r = simulation.run(observers, {&checkpoint_writer, p.checkpoint.interval,
                                   resume_from ? &*resume_from : nullptr,
                                   p.checkpoint.stop_after_steps});
  }
  catch (const SimulationError& e)
  {
    if (progress)
      progress->finish();
    // Keep what was written (time_series.csv up to the failure) and say so.
    std::ofstream out(dir + "/summary.json");
    JsonWriter json(out);
    json.begin_object().value("status", "failed").value("reason", e.what()).end_object();
    throw;
  }
  // Only an explicit run needs (and has already computed) 2/omega_max: the
  // banded eigensolver dominates a fine-grid BDF-2 run's start-up otherwise.
  r.stability_limit = p.time_integration.integrator == IntegratorType::half_explicit
                          ? simulation.explicit_stability_limit()
                          : std::numeric_limits<double>::quiet_NaN();
  timer.enter_subsection("output (summary, plots)");
  write_summary(dir + "/summary.json", p, simulation, r, stats, events,
                contact ? &contact->result() : nullptr, energy,
                reference ? &*reference : nullptr);
  if (contact)
    write_contact_force(dir + "/contact_force.csv", *contact);

  if (has_contact)
    out << std::setprecision(6) << "  first time point t = " << first.t
        << " s: lambda_p = " << first.lambda_p
        << " N (lambda_p(0) = " << p.pantograph.initial_contact_force << " N)\n";
  out << "  " << r.integrator.steps << " steps in " << std::setprecision(3)
      << r.time_loop_seconds
      << " s; active-set changes: " << r.integrator.active_set_changes << '\n';
  if (has_contact)
    out << std::setprecision(5) << "  contact force: max " << stats.contact_force_max()
        << " N, min " << stats.contact_force_min() << " N, mean "
        << stats.contact_force_mean() << " N, std " << stats.contact_force_std()
        << " N\n";
  if (reference)
    for (const auto& probe : reference->probes())
      out << std::setprecision(4) << "  series solution at x = " << probe.x
          << " m: max |w - w_series| = " << probe.max_error << " m, "
          << 100. * probe.relative() << " % of max |w_series| = " << probe.max_reference
          << " m\n";
  if (energy.count > 0)
    out << std::setprecision(6) << "  energy: initial " << energy.initial << " J, final "
        << energy.final << " J, max |E - E(0)| / |E(0)| = " << std::setprecision(3)
        << energy.relative_variation() << '\n';
  const auto slack = stats.dropper_slack_intervals();
  for (unsigned int j = 0; j < slack.size(); ++j)
    out << "  dropper " << j + 1 << " slack: " << format_intervals(slack[j]) << '\n';
  if (has_contact)
    out << "  contact lost: " << format_intervals(stats.contact_loss_intervals()) << '\n';
  out << std::setprecision(3) << "  max constraint residual: position "
      << stats.max_position_residual() << " m, velocity " << stats.max_velocity_residual()
      << " m/s\n";
  if (p.output.verbosity == Verbosity::detailed)
    out << "  active-set iterations: " << r.integrator.active_set_iterations << '\n';
  if (contact)
    print_statistics(out, contact->result());
  if (p.output.plots && contact)
  {
    std::ostringstream title;
    title << to_string(p.discretisation.method) << " + "
          << to_string(p.time_integration.integrator) << ", v_p = " << p.pantograph.speed
          << " m/s";
    const bool series_drawn =
        plot_time_series(dir, p.catenary.n_droppers(),
                         simulation.layout().pantograph_coordinates, title.str());
    const bool drawn =
        plot_contact_force_statistics(dir, contact->result(), title.str()) &&
        series_drawn;
    if (!drawn)
      out << (gnuplot_available()
                  ? "  (gnuplot failed on a .gp script in the directory)\n"
                  : "  (gnuplot not found: wrote the .gp scripts without "
                    "PNG plots)\n");
  }
  timer.leave_subsection();
  out << "  wrote time_series.csv" << (contact ? ", contact_force.csv" : "")
      << ", summary.json"
      << (p.output.plots && contact
              ? ", contact_force.png, dropper_forces.png, pantograph.png, "
                "contact_force_statistics.png"
              : "")
      << (vtu ? ", solution.pvd with " + std::to_string(vtu->frames().size()) +
                    " frames in vtu/"
              : "")
      << " to " << dir << '\n';
  if (p.output.verbosity == Verbosity::detailed)
    list_files(out, dir);
  if (p.output.verbosity != Verbosity::quiet)
    timer.print_summary();
}
} // namespace pantocat
