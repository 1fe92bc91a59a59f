#include <pantocat/base/input_error.h>
#include <pantocat/base/safe_files.h>
#include <pantocat/io/json_writer.h>
#include <pantocat/io/run_summary.h>
#include <pantocat/io/statistics_report.h>
#include <pantocat/scene/steady_arms.h>
#include <pantocat/simulation/run_events.h>
#include <pantocat/simulation/switch_episodes.h>
#include <pantocat/time/integrator_registry.h>

#include <algorithm>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace pantocat
{
const ContactStatistics* RunRecord::first_contact() const
{
  for (const ContactStatistics* c : contacts)
    if (c != nullptr)
      return c;
  return nullptr;
}

double RunRecord::position_at(const unsigned int k, const double t) const
{
  return runner.case_data().scene.pantographs[k].parameters.position(t);
}

namespace
{
void write_force(JsonWriter& json, const RunStatistics::ForceStatistics& f)
{
  json.begin_object("contact_force")
      .value("max", f.max)
      .value("min", f.min)
      .value("mean", f.mean)
      .value("std", f.std())
      .end_object();
}

/// The droppers' slack events that begin while the pantograph of @p s is in its window.
DropperSlackEvents slack_in_window(const RunStatistics& run,
                                   const ContactForceStatistics& s)
{
  return run.dropper_slack_events(s.first_time, s.last_time);
}

/// The events of the constraints named @p only (every constraint's if empty).
void write_events(JsonWriter& json, const std::vector<ConstraintEvent>& events,
                  const std::vector<std::string>& only = {})
{
  json.begin_array("events");
  for (const ConstraintEvent& e : events)
    if (only.empty() || std::find(only.begin(), only.end(), e.constraint) != only.end())
    {
      json.begin_object()
          .value("t", e.t)
          .value("constraint", e.constraint)
          .value("kind", e.kind);
      if (closes(e))
        json.value("impulse", e.impulse); // [N s], inelastic (Sec. 5.3)
      json.end_object();
    }
  json.end_array();
}

/// The episodes of one constraint (switch_episodes()), as objects.
void write_episodes(JsonWriter& json, const std::string& key,
                    const std::vector<Interval>& open, const double gap)
{
  json.begin_array(key);
  for (const SwitchEpisode& e : switch_episodes(open, gap))
    json.begin_object()
        .value("from", e.span.first)
        .value("to", e.span.second)
        .value("intervals", static_cast<unsigned long>(e.intervals))
        .value("open_time", e.open_time)
        .end_object();
  json.end_array();
}

/// Impacts (inelastic, Sec. 5.3): count, summed and largest impulse [N s].
void write_impulses(JsonWriter& json, const std::string& name,
                    const RunStatistics::ImpulseStatistics& s)
{
  json.begin_object(name)
      .value("count", s.count)
      .value("total_impulse", s.total)
      .value("max_impulse", s.max)
      .end_object();
}

void write_pantographs(JsonWriter& json, const RunRecord& r,
                       const std::vector<ConstraintEvent>& events)
{
  const SimulationLayout& layout = r.runner.layout();
  const Case& c = r.runner.case_data();
  json.begin_array("pantographs");
  for (unsigned int k = 0; k < layout.pantographs.size(); ++k)
  {
    const PantographLayout& p = layout.pantographs[k];
    const PantographParameters& data = c.scene.pantographs[k].parameters;
    json.begin_object()
        .value("name", p.name)
        .value("model", p.model)
        .value("initial_position", data.initial_position)
        .value("speed", data.speed)
        .value("speed_kmh", 3.6 * data.speed);
    if (p.has_contact())
    {
      write_force(json, r.statistics.contact_force(k));
      if (r.contacts[k] != nullptr)
        write_statistics(json, r.contacts[k]->result(),
                         slack_in_window(r.statistics, r.contacts[k]->result()));
      write_assessment(json, k < r.assessments.size() ? r.assessments[k] : Assessment{});
      json.intervals("contact_loss_intervals", r.statistics.contact_loss_intervals(k));
      write_episodes(json, "contact_loss_episodes",
                     r.statistics.contact_loss_intervals(k), r.episode_resolution);
      // Over its contact wires (one for a single section).
      RunStatistics::ImpulseStatistics impacts;
      std::vector<std::string> names;
      for (const unsigned int i : p.wire_contacts)
      {
        const RunStatistics::ImpulseStatistics& s = r.statistics.impulses(i);
        impacts.count += s.count;
        impacts.total += s.total;
        impacts.max = std::max(impacts.max, s.max);
        names.push_back(layout.constraint_names[i]);
      }
      write_impulses(json, "impacts", impacts);
      write_events(json, events, names);
    }
    json.end_object();
  }
  json.end_array();
}
} // namespace

void write_run_summary(const std::string& file, const RunRecord& r)
{
  const Case& c = r.runner.case_data();
  const SemiDiscreteSystem& system = r.runner.system();
  const RunStatistics& stats = r.statistics;
  const auto events = run_events(r.runner.layout(), r.result.integrator, r.events);
  std::ostringstream out;
  JsonWriter json(out);
  json.begin_object()
      .value("status", "completed")
      .value("program", std::string("pantocat-fem ") + PANTOCAT_VERSION)
      .value("start", c.scene.start == Start::paper ? "paper" : "static equilibrium")
      .value("discretisation", to_string(c.discretisation.method))
      .value("number_of_intervals",
             static_cast<unsigned long>(c.discretisation.n_intervals))
      .value("integrator", c.time_integration.integrator)
      .value("time_step", c.time_integration.time_step)
      .value("speed", c.scene.pantographs[0].parameters.speed)
      .value("end_time", r.result.end_time)
      .value("unknowns", static_cast<unsigned long>(system.n_dofs()))
      .value("constraints", static_cast<unsigned long>(system.n_constraints()));
  json.begin_array("scene");
  for (const std::string& effect : r.runner.active_effects())
    json.value("", effect);
  json.end_array();
  json.begin_object("inputs"); // what the case set; every other entry has its default
  for (const auto& [name, value] : r.inputs)
    json.value(name, value);
  json.end_object();
  write_pantographs(json, r, events);
  if (const ContactStatistics* first = r.first_contact())
  {
    write_force(json, stats.first_contact_force());
    write_statistics(json, first->result(), slack_in_window(stats, first->result()));
  }
  if (r.energy != nullptr && r.energy->count > 0)
    json.begin_object("energy")
        .value("initial", r.energy->initial)
        .value("min", r.energy->min)
        .value("max", r.energy->max)
        .value("final", r.energy->final)
        .value("max_relative_variation", r.energy->relative_variation())
        .end_object();
  if (r.series != nullptr)
  {
    json.begin_array("series_reference");
    for (const auto& probe : r.series->probes())
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
  write_slack_events(json, "dropper_slack_events", stats.dropper_slack_events());
  json.value("episode_resolution", r.episode_resolution);
  json.begin_array("dropper_slack_episodes");
  for (const auto& list : stats.dropper_slack_intervals())
    write_episodes(json, "", list, r.episode_resolution);
  json.end_array();
  if (r.runner.layout().has_contact())
  {
    json.intervals("contact_loss_intervals", stats.contact_loss_intervals());
    write_episodes(json, "contact_loss_episodes", stats.contact_loss_intervals(),
                   r.episode_resolution);
  }
  if (r.line != nullptr && !r.line->evaluations().empty())
    write_line_windows(json, *r.line, r.runner.layout());
  write_impulses(json, "dropper_impacts", stats.dropper_impulses());
  json.value("max_droppers_slack_at_once",
             static_cast<unsigned long>(stats.max_droppers_slack_at_once()));
  // Events: located in time by the integrator (IDA's root finding), or at
  // step resolution from the reported time points.
  json.value("event_resolution",
             r.result.integrator.events_localised ? "localised" : "step");
  write_events(json, events);
  if (!r.result.integrator.counters.empty())
  {
    json.begin_object("integrator_counters");
    for (const auto& [name, value] : r.result.integrator.counters)
      json.value(name, static_cast<unsigned long>(value));
    json.end_object();
  }
  json.value("steps", r.result.integrator.steps)
      .value("active_set_changes", r.result.integrator.active_set_changes)
      .value("active_set_iterations", r.result.integrator.active_set_iterations);
  json.begin_object("max_constraint_residual")
      .value("position", stats.max_position_residual())
      .value("velocity", stats.max_velocity_residual())
      .end_object();
  const GuardExtremes& g = r.result.guards;
  json.begin_object("guards")
      .value("max_drift", g.max_drift)
      .value("max_multiplier", g.max_multiplier)
      .value("reference_force", g.reference_force)
      .value("max_energy_increase", g.max_energy_increase)
      .value("min_energy_increase", g.min_energy_increase)
      .value("reference_energy", g.reference_energy)
      .end_object();
  json.value("stability_limit_explicit", r.result.stability_limit)
      .value("time_loop_seconds", r.result.time_loop_seconds)
      .end_object();
  write_file_atomically(file, out.str());
}

void write_failed_summary(const std::string& file, const std::string& phase,
                          const std::string& reason,
                          const std::vector<PassedWindow>& passed)
{
  std::ostringstream out;
  JsonWriter json(out);
  json.begin_object()
      .value("status", "failed")
      .value("phase", phase)
      .value("reason", reason);
  if (!passed.empty())
  {
    json.begin_array("passed_windows");
    for (const PassedWindow& w : passed)
    {
      json.begin_object().value("pantograph", w.pantograph);
      write_statistics(json, w.statistics, w.slack_in_window);
      write_assessment(json, w.assessment);
      json.end_object();
    }
    json.end_array();
  }
  json.end_object();
  write_file_atomically(file, out.str());
}

namespace
{
/**
 * "[t0, t1], ...": the intervals, or, where a cascade's intervals merge into
 * an episode (reclosures shorter than @p gap), the episodes with the number
 * of their intervals and the time open within them.
 */
std::string format_intervals(const std::vector<Interval>& list, const double gap)
{
  if (list.empty())
    return "none";
  const std::vector<SwitchEpisode> episodes = switch_episodes(list, gap);
  std::ostringstream s;
  s << std::setprecision(4);
  for (std::size_t i = 0; i < episodes.size(); ++i)
  {
    const SwitchEpisode& e = episodes[i];
    s << (i ? ", " : "") << '[' << e.span.first << ", " << e.span.second << ']';
    if (e.intervals > 1)
      s << " (" << e.intervals << " intervals, open " << std::setprecision(3)
        << 1e3 * e.open_time << " ms)" << std::setprecision(4);
  }
  if (episodes.size() < list.size())
    s << "; " << list.size() << " intervals in " << episodes.size()
      << (episodes.size() == 1 ? " episode" : " episodes") << " (reclosures < "
      << 1e3 * gap << " ms merged)";
  return s.str();
}
} // namespace

void print_case_summary(std::ostream& out, const CaseRunner& runner)
{
  const Case& c = runner.case_data();
  const SimulationLayout& layout = runner.layout();
  std::size_t arms = 0;
  for (const CatenaryParameters& section : runner.sections())
    arms += SteadyArms::positions(c.scene, section).size();
  out << std::setprecision(6) << "  case: ";
  if (c.line.is_line())
    out << c.line.n_sections << " tension sections of " << c.catenary.number_of_spans()
        << " spans (" << c.line_length() << " m) with " << c.line.n_sections - 1
        << (c.line.n_sections == 2 ? " overlap" : " overlaps") << " of "
        << c.line.overlap_spans << (c.line.overlap_spans == 1 ? " span" : " spans")
        << ", ";
  else
    out << c.catenary.number_of_spans()
        << (c.catenary.number_of_spans() == 1 ? " span" : " spans") << " ("
        << c.catenary.length() << " m), ";
  if (layout.dropper_indices.empty())
    out << "no droppers";
  else
    out << layout.dropper_indices.size() << ' ' << to_string(c.scene.droppers)
        << " droppers";
  if (arms > 0)
    out << ", " << arms << " steady arms";
  if (!c.catenary.stitch_wires.empty())
    out << ", " << c.catenary.stitch_wires.size() * runner.sections().size()
        << " stitch wires";
  for (unsigned int k = 0; k < layout.pantographs.size(); ++k)
  {
    const PantographCase& p = c.scene.pantographs[k];
    out << (k == 0 ? "; " : ", ") << layout.pantographs[k].name << ": " << p.model;
    if (p.has_body())
      out << " (" << layout.pantographs[k].coordinates.size() << " bodies, "
          << p.contact_law() << " contact)";
    out << " at " << std::setprecision(4) << 3.6 * p.parameters.speed << " km/h";
  }
  const SemiDiscreteSystem& system = runner.system();
  out << "; " << system.n_dofs() << " unknowns, " << system.n_constraints()
      << " constraints\n";
  for (const PantographLayout* p : layout.contacts())
    out << std::setprecision(5) << "  start: "
        << (c.scene.start == Start::paper ? "the paper's (13)" : "static equilibrium")
        << (layout.contacts().size() > 1 ? ", " + p->name : std::string())
        << ": lambda_p(0) = " << p->initial_contact_force << " N (static force "
        << p->static_force << " N)\n";
}

void print_scene(std::ostream& out, const CaseRunner& runner)
{
  const SemiDiscreteSystem& system = runner.system();
  const SimulationLayout& layout = runner.layout();
  out << "  scene: " << runner.active_effects().size() << " effects\n";
  for (const std::string& effect : runner.active_effects())
    out << "    " << effect << '\n';
  if (!runner.inactive_effects().empty())
  {
    out << "  left out (not assembled):";
    for (const std::string& name : runner.inactive_effects())
      out << (name == runner.inactive_effects().front() ? " " : ", ") << name;
    out << '\n';
  }
  out << "  problem size: " << system.n_dofs() << " unknowns (";
  for (const DofBlock& b : system.blocks)
    out << (&b == &system.blocks.front() ? "" : ", ") << b.name << ' ' << b.size;
  std::size_t contacts = 0; // one per pantograph and contact wire it can touch
  for (const PantographLayout* p : layout.contacts())
    contacts += p->wire_contacts.size();
  out << "), " << system.n_constraints() << " constraints ("
      << layout.dropper_indices.size() << " droppers";
  if (contacts == 1)
    out << ", contact";
  else if (contacts > 1)
    out << ", " << contacts << " contacts";
  // The rest are the carrier supports held fixed (CarrierSupports) and the
  // stitch wires' clamps (StitchWires).
  std::size_t clamps = 0;
  for (const std::string& name : layout.constraint_names)
    clamps += name.find("stitch wire ") != std::string::npos;
  const std::size_t supports =
      system.n_constraints() - layout.dropper_indices.size() - contacts - clamps;
  if (supports > 0)
    out << ", " << supports << " carrier supports";
  if (clamps > 0)
    out << ", " << clamps << " stitch-wire clamps";
  out << ")\n";
}

namespace
{
/// Up to this many episodes of lost contact, the screen lists them.
constexpr std::size_t max_episodes_listed = 3;

/// "[5.915, 5.926] s (x_p 525.8-526.7 m)" for the first few episodes of @p list.
std::string located_episodes(const RunRecord& r, const unsigned int k,
                             const std::vector<Interval>& list)
{
  if (list.empty())
    return "none";
  const std::vector<SwitchEpisode> episodes = switch_episodes(list, r.episode_resolution);
  std::ostringstream s;
  s << std::setprecision(4);
  for (std::size_t i = 0; i < std::min(episodes.size(), max_episodes_listed); ++i)
  {
    const auto& [t0, t1] = episodes[i].span;
    s << (i ? ", " : "") << '[' << t0 << ", " << t1 << "] s (x_p " << r.position_at(k, t0)
      << "-" << r.position_at(k, t1) << " m)";
  }
  if (episodes.size() > max_episodes_listed)
    s << " and " << episodes.size() - max_episodes_listed
      << (episodes.size() - max_episodes_listed == 1 ? " more episode"
                                                     : " more episodes");
  return s.str();
}

/**
 * "; each at most one time step long ...": the note for contact-loss
 * @p intervals that all last one step @p dt or less (a rigid contact that
 * chatters at this step, or the grid's answer to an impact), "" otherwise.
 */
std::string single_step_note(const std::vector<Interval>& intervals, const double dt)
{
  if (intervals.empty() ||
      std::any_of(intervals.begin(), intervals.end(),
                  [&](const Interval& i) { return i.second - i.first > 1.5 * dt; }))
    return "";
  std::ostringstream s;
  s << std::setprecision(3) << "; each at most one time step long (dt = " << dt
    << " s): the contact chatters at this step; rerun with a smaller step (or a "
       "finer grid after an impact) to tell whether the loss is real";
  return s.str();
}

/// The whole run's contact force of pantograph @p k, its extremes with their positions.
void print_whole_run_force(std::ostream& out, const RunRecord& r, const unsigned int k,
                           const std::string& name)
{
  const auto& f = r.statistics.contact_force(k);
  out << std::setprecision(5) << "  " << name << "whole run: contact force max " << f.max
      << " N at x_p = " << std::setprecision(4) << f.max_position << " m, min "
      << std::setprecision(5) << f.min << " N at x_p = " << std::setprecision(4)
      << f.min_position << " m, mean " << std::setprecision(5) << f.mean << " N, std "
      << f.std() << " N\n";
}

/// Slack per dropper: every interval (detailed), or the events in one line.
void print_dropper_slack(std::ostream& out, const RunRecord& r, const bool detailed)
{
  const auto slack = r.statistics.dropper_slack_intervals();
  if (detailed)
    for (unsigned int j = 0; j < slack.size(); ++j)
      if (!slack[j].empty())
        out << "  dropper " << j + 1
            << " slack: " << format_intervals(slack[j], r.episode_resolution) << '\n';
  if (!slack.empty())
    out << "  dropper slack events in the whole run: "
        << describe_slack_events(r.statistics.dropper_slack_events()) << '\n';
}
} // namespace

namespace
{
/// The columns of print_statistics_side_by_side(): each pantograph in contact.
std::vector<PantographFigures> pantograph_figures(const RunRecord& r)
{
  std::vector<PantographFigures> columns;
  for (unsigned int k = 0; k < r.contacts.size(); ++k)
    if (const ContactStatistics* c = r.contacts[k])
      columns.push_back({r.runner.layout().pantographs[k].name, &c->result(),
                         slack_in_window(r.statistics, c->result()),
                         k < r.assessments.size() ? &r.assessments[k] : nullptr});
  return columns;
}
} // namespace

void print_run_report(std::ostream& out, const RunRecord& r, const bool detailed)
{
  const SimulationLayout& layout = r.runner.layout();
  const RunStatistics& stats = r.statistics;
  const bool several = layout.contacts().size() > 1;
  const auto name = [&](const unsigned int k)
  { return several ? layout.pantographs[k].name + ": " : std::string(); };
  if (detailed)
    for (const PantographLayout* p : layout.contacts())
      out << std::setprecision(6) << "  " << (several ? p->name + ": " : "")
          << "first time point t = " << r.first_point.t << " s: lambda_p = " <<
          [&]
      {
        double sum = 0.; // over the pantograph's contact wires
        for (const unsigned int i : p->wire_contacts)
          sum += r.first_point.lambda[i];
        return sum;
      }()
          << " N (lambda_p(0) = " << p->initial_contact_force << " N)\n";
  out << "  " << r.result.integrator.steps << " steps in " << std::setprecision(3)
      << r.result.time_loop_seconds
      << " s; active-set changes: " << r.result.integrator.active_set_changes << '\n';
  for (unsigned int k = 0; k < layout.pantographs.size(); ++k)
    if (layout.pantographs[k].has_contact())
      print_whole_run_force(out, r, k, name(k));
  if (r.series != nullptr)
    for (const auto& probe : r.series->probes())
      out << std::setprecision(4) << "  series solution at x = " << probe.x
          << " m: max |w - w_series| = " << probe.max_error << " m, "
          << 100. * probe.relative() << " % of max |w_series| = " << probe.max_reference
          << " m\n";
  if (r.energy != nullptr && r.energy->count > 0)
    out << std::setprecision(6) << "  energy: initial " << r.energy->initial
        << " J, final " << r.energy->final
        << " J, max |E - E(0)| / |E(0)| = " << std::setprecision(3)
        << r.energy->relative_variation() << '\n';
  print_dropper_slack(out, r, detailed);
  for (unsigned int k = 0; k < layout.pantographs.size(); ++k)
    if (layout.pantographs[k].has_contact())
      out << "  " << name(k) << "contact lost in the whole run: "
          << (detailed ? format_intervals(stats.contact_loss_intervals(k),
                                          r.episode_resolution)
                       : located_episodes(r, k, stats.contact_loss_intervals(k)))
          << single_step_note(stats.contact_loss_intervals(k), r.runner.time_step())
          << '\n';
  if (r.line != nullptr)
    print_line_windows(out, *r.line, layout, detailed);
  out << std::setprecision(3) << "  max constraint residual: position "
      << stats.max_position_residual() << " m, velocity " << stats.max_velocity_residual()
      << " m/s\n";
  if (detailed)
    out << "  active-set iterations: " << r.result.integrator.active_set_iterations
        << '\n';
  if (several && !detailed)
  {
    print_statistics_side_by_side(out, pantograph_figures(r));
    out << "  (each pantograph's raw and low-passed figures and every criterion: "
           "report.html, Output/Verbosity = detailed)\n";
    return;
  }
  for (unsigned int k = 0; k < r.contacts.size(); ++k)
    if (r.contacts[k] != nullptr)
    {
      if (several)
        out << "  " << layout.pantographs[k].name << ":\n";
      print_statistics(out, r.contacts[k]->result(),
                       slack_in_window(stats, r.contacts[k]->result()));
      if (k < r.assessments.size())
        print_assessment(out, r.assessments[k]);
    }
}
} // namespace pantocat
