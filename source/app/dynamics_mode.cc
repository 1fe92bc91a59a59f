#include <pantocat/app/run_modes.h>
#include <pantocat/base/input_error.h>
#include <pantocat/base/safe_files.h>
#include <pantocat/catenary/wave_speeds.h>
#include <pantocat/io/line_response_plots.h>
#include <pantocat/io/plots.h>
#include <pantocat/io/progress_meter.h>
#include <pantocat/io/run_report.h>
#include <pantocat/io/run_summary.h>
#include <pantocat/io/statistics_report.h>
#include <pantocat/io/time_series_writer.h>
#include <pantocat/io/vtu_time_series_writer.h>
#include <pantocat/scene/steady_arms.h>
#include <pantocat/simulation/case_runner.h>
#include <pantocat/simulation/checkpoint.h>
#include <pantocat/simulation/line_windows.h>

#include <deal.II/base/timer.h>

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>

namespace pantocat
{
namespace
{
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

/// Names of the plotted columns of time_series.csv, from the layout.
struct PlottedColumns
{
  std::vector<std::string> contact_forces, dropper_forces, coordinates;
};

PlottedColumns plotted_columns(const SimulationLayout& layout)
{
  PlottedColumns c;
  for (const PantographLayout* p : layout.contacts())
    for (const std::string& name : TimeSeriesWriter::contact_columns(*p, "lambda_p"))
      c.contact_forces.push_back(name);
  // At most 9 droppers, evenly spread (a section has ~90): more lines make the
  // plot unreadable, and gnuplot reads the whole CSV once per line.
  const unsigned int m = layout.dropper_indices.size(), shown = std::min(m, 9u);
  for (unsigned int k = 0; k < shown; ++k)
  {
    const unsigned int j = shown == m ? k : (k * (m - 1) + (shown - 1) / 2) / (shown - 1);
    c.dropper_forces.push_back("lambda_d" + std::to_string(j + 1));
  }
  for (const PantographLayout& p : layout.pantographs)
    for (const auto& name : p.coordinates)
      c.coordinates.push_back(name + p.column_suffix);
  return c;
}

/// The columns of contact_force.csv: every pantograph in contact, in layout order.
std::vector<ContactForceColumns> contact_force_columns(const RunRecord& record)
{
  std::vector<ContactForceColumns> columns;
  const SimulationLayout& layout = record.runner.layout();
  for (unsigned int k = 0; k < record.contacts.size(); ++k)
    if (record.contacts[k] != nullptr)
      columns.push_back({record.contacts[k], layout.pantographs[k].column_suffix});
  return columns;
}

/// Each pantograph's window assessed by subsection Assessment (none for the whole run).
std::vector<Assessment> assess_windows(const ProgramParameters& p,
                                       const RunRecord& record)
{
  std::vector<Assessment> assessments(record.contacts.size());
  if (!p.assessment.enabled)
    return assessments;
  for (unsigned int k = 0; k < record.contacts.size(); ++k)
    if (record.contacts[k] != nullptr && !record.contacts[k]->result().window.whole_run())
      assessments[k] = assess(record.contacts[k]->result(),
                              p.scene.pantographs[k].parameters.speed, p.assessment);
  return assessments;
}

/**
 * The windows the pantographs in contact had passed when the run failed
 * (ContactStatistics::passed_window()), assessed, and printed marked as such.
 */
std::vector<PassedWindow>
passed_windows(std::ostream& out, const ProgramParameters& p,
               const SimulationLayout& layout,
               const std::vector<std::unique_ptr<ContactStatistics>>& contacts,
               const RunStatistics& stats)
{
  std::vector<PassedWindow> passed;
  for (unsigned int k = 0; k < contacts.size(); ++k)
    if (contacts[k])
      if (std::optional<ContactForceStatistics> s = contacts[k]->passed_window())
      {
        PassedWindow w{layout.pantographs[k].name,
                       *s,
                       stats.dropper_slack_events(s->first_time, s->last_time),
                       {}};
        if (p.assessment.enabled)
          w.assessment =
              assess(*s, p.scene.pantographs[k].parameters.speed, p.assessment);
        out << "  the run failed after the evaluation window of " << w.pantograph
            << " was passed; its figures up to "
            << ContactStatistics::passed_window_margin
            << " s after the window (summary.json: passed_windows):\n";
        print_statistics(out, w.statistics, w.slack_in_window);
        print_assessment(out, w.assessment);
        passed.push_back(std::move(w));
      }
  return passed;
}

/// The plots of the contact force over x_p, one per pantograph in contact.
std::vector<ForceOverXPlot> force_over_x_plots(const RunRecord& record)
{
  const SimulationLayout& layout = record.runner.layout();
  const bool several = layout.contacts().size() > 1;
  std::vector<ForceOverXPlot> plots;
  for (unsigned int k = 0; k < record.contacts.size(); ++k)
    if (const ContactStatistics* c = record.contacts[k])
    {
      const std::string& name = layout.pantographs[k].name;
      const std::vector<double>& x = c->series().x_p;
      const Assessment* assessment =
          k < record.assessments.size() && !record.assessments[k].criteria.empty()
              ? &record.assessments[k]
              : nullptr;
      plots.push_back({contact_force_over_x_file(name, several), name,
                       layout.pantographs[k].column_suffix, x.front(), x.back(),
                       &c->result(), assessment});
    }
  return plots;
}

/// The PNG files a run draws (asked), the files gnuplot wrote (drawn: PNG
/// and SVG) and the pictures of report.html.
struct Plots
{
  std::vector<std::string> asked, drawn;
  std::vector<ReportFigure> figures;
  /// True if a PNG file asked for was not drawn.
  bool missing() const
  {
    return std::any_of(asked.begin(), asked.end(),
                       [&](const std::string& png) {
                         return std::find(drawn.begin(), drawn.end(), png) == drawn.end();
                       });
  }
};

/// The plots along the line (uplift, dropper slack) of the first contact's window.
std::vector<PlotScript> line_response_scripts(const std::string& dir,
                                              const RunRecord& record,
                                              const std::string& title,
                                              std::vector<ReportFigure>& figures)
{
  const LineResponseFrame frame{record.runner.support_positions(), title};
  const std::vector<double> droppers = record.runner.dropper_positions();
  const ContactStatistics& first = *record.first_contact();
  const std::size_t k =
      std::find(record.contacts.begin(), record.contacts.end(), &first) -
      record.contacts.begin();
  const Assessment* assessment =
      k < record.assessments.size() ? &record.assessments[k] : nullptr;
  std::vector<PlotScript> scripts{
      uplift_script(dir, first.result(), droppers, assessment, frame),
      dropper_slack_script(dir, droppers, record.statistics.dropper_slack_intervals(),
                           first.result().window, frame)};
  if (!scripts[0].outputs.empty())
    figures.push_back({"uplift.svg", "Uplift of the contact wire: the largest rise over "
                                     "its static height at the droppers (whole run) and "
                                     "at the steady arms in the window."});
  if (!scripts[1].outputs.empty())
    figures.push_back(
        {"dropper_slack.svg",
         "Dropper slack per dropper: the time slack and the number of slack "
         "intervals in the whole run."});
  return scripts;
}

/// The PNG plots of a run (and the SVG copies for report.html).
Plots draw_plots(const std::string& dir, const ProgramParameters& p,
                 const RunRecord& record)
{
  const CaseRunner& runner = record.runner;
  std::ostringstream title;
  title << to_string(p.discretisation.method) << " + " << p.time_integration.integrator
        << ", v_p = " << std::setprecision(4) << 3.6 * p.pantograph().speed << " km/h ("
        << p.pantograph().speed << " m/s)";
  const PlottedColumns c = plotted_columns(runner.layout());
  std::vector<PlotScript> scripts{
      time_series_script(dir, TimeSeriesWriter::column_names(runner.layout()),
                         c.contact_forces, c.dropper_forces, c.coordinates, title.str()),
      contact_force_statistics_script(dir, record.first_contact()->result(),
                                      title.str())};
  Plots plots{{"contact_force.png", "dropper_forces.png", "pantograph.png",
               "contact_force_statistics.png"},
              {},
              {}};
  const std::vector<ForceOverXPlot> over_x = force_over_x_plots(record);
  if (!over_x.empty())
    scripts.push_back(contact_force_over_x_script(
        dir, contact_force_column_names(contact_force_columns(record)), over_x,
        runner.support_positions(), title.str()));
  for (const ForceOverXPlot& plot : over_x)
  {
    plots.asked.push_back(plot.png);
    plots.figures.push_back(
        {svg_file_of(plot.png),
         (over_x.size() > 1 ? "Contact force of " + plot.name
                            : std::string("Contact force")) +
             " over the pantograph's position: the evaluation window shaded, its F_m and "
             "the assessment's force limits across it."});
  }
  for (PlotScript& s : line_response_scripts(dir, record, title.str(), plots.figures))
    if (!s.outputs.empty())
    {
      plots.asked.push_back(s.outputs.front());
      scripts.push_back(std::move(s));
    }
  if (scripts.front().outputs.empty())
    scripts.erase(scripts.begin()); // no time-series column to draw
  plots.drawn = run_gnuplot(dir, scripts);
  return plots;
}
} // namespace

void run_dynamics(const ProgramParameters& p, std::ostream& out, RunPhase& phase)
{
  dealii::TimerOutput timer(out, dealii::TimerOutput::never,
                            dealii::TimerOutput::wall_times);
  timer.enter_subsection("setup (assembly, initial state)");
  CaseRunner runner(p.make_case(), {p.output.probe_positions, p.output.energy});
  runner.check(); // before any output is written
  const std::string& dir = p.output.directory;
  // A checkpoint to continue from is checked (its parameters) before any
  // output is touched; a fresh run removes a checkpoint of an earlier one.
  const std::string checkpoint_file = dir + "/checkpoint.bin";
  std::optional<CheckpointReader> resume_from;
  if (p.checkpoint.resume)
    resume_from.emplace(checkpoint_file, p.fingerprint, runner.number_of_steps(),
                        runner.time_step());
  const CheckpointWriter checkpoint_writer(checkpoint_file, p.fingerprint);
  // The series solution refuses what it cannot compare (a speed ramp, a speed
  // above the wave speed): before any output is touched too.
  std::optional<MovingLoadComparison> reference;
  if (p.scene.is_classical_moving_load() && !p.output.probe_positions.empty())
    reference.emplace(moving_load_series(runner.case_data()));
  timer.leave_subsection();
  phase.begin("time loop"); // clears the results of an earlier run
  out << "Dynamic run: " << to_string(p.discretisation.method)
      << ", N+1 = " << p.discretisation.n_intervals << ", "
      << p.time_integration.integrator << ", dt = " << runner.time_step() << " s";
  if (runner.time_step() != p.time_integration.time_step)
    out << " (" << p.time_integration.time_step << " s asked, shortened so that "
        << runner.number_of_steps() << " steps end at the final position)";
  out << ", v_p = " << 3.6 * p.pantograph().speed << " km/h (" << p.pantograph().speed
      << " m/s), x_p from " << p.pantograph().initial_position << " to "
      << p.pantograph().final_position << " m\n";
  const bool detailed = p.output.verbosity == Verbosity::detailed;
  if (detailed)
    print_scene(out, runner);
  else
    print_case_summary(out, runner);
  if (p.scene.contact_wire == WireModel::elastic && !p.scene.pantographs[0].is_absent())
    print_wave_speeds(out, wave_speeds(runner.case_data().catenary, p.pantograph().speed),
                      !detailed);
  if (resume_from)
    out << "  resuming from " << checkpoint_file << " after step " << resume_from->step()
        << '\n';

  TimeSeriesWriter series(dir + "/time_series.csv", p.output.time_series_interval);
  RunStatistics stats;
  EventLog events;
  FirstTimePoint first;
  EnergyRange energy;
  std::vector<SimulationObserver*> observers{&series, &stats, &events};
  // Observers that are not asked for are not attached: they cost nothing.
  // One contact-statistics observer per pantograph in contact.
  const SimulationLayout& layout = runner.layout();
  std::vector<std::unique_ptr<ContactStatistics>> contacts(layout.pantographs.size());
  if (layout.has_contact())
    observers.push_back(&first);
  const UpliftPoints uplift = runner.uplift_points();
  const std::vector<double> window_supports =
      runner.case_data().window_supports(p.statistics.window_section);
  for (unsigned int k = 0; k < layout.pantographs.size(); ++k)
    if (layout.pantographs[k].has_contact())
      observers.push_back((contacts[k] = std::make_unique<ContactStatistics>(
                               p.statistics, window_supports, uplift, k))
                              .get());
  LineWindows line_windows(p.statistics, runner, layout);
  for (SimulationObserver* o : line_windows.observers())
    observers.push_back(o);
  if (p.output.energy)
    observers.push_back(&energy);
  if (reference)
    observers.push_back(&*reference);
  std::optional<VtuTimeSeriesWriter> vtu;
  if (p.output.vtu_interval > 0.)
    observers.push_back(&vtu.emplace(dir, p.output.vtu_interval, runner.time_step(),
                                     p.output.vtu_subdivisions, runner.discretisation(),
                                     runner.system(), &timer));
  std::optional<ProgressMeter> progress;
  if (p.output.verbosity != Verbosity::quiet && stderr_is_terminal())
    observers.push_back(&progress.emplace(std::cerr, runner.case_data().end_time()));
  CaseRunner::Result r;
  try
  {
    const dealii::TimerOutput::Scope scope(timer, "time loop (includes the VTU frames)");
    r = runner.run(observers, {&checkpoint_writer, p.checkpoint.interval,
                               resume_from ? &*resume_from : nullptr,
                               p.checkpoint.stop_after_steps});
  }
  catch (const SimulationError&)
  {
    if (progress)
      progress->finish();
    phase.keep_passed_windows(passed_windows(out, p, layout, contacts, stats));
    throw; // time_series.csv is kept up to the failure; RunPhase says so
  }
  phase.begin("output");
  timer.enter_subsection("output (summary, plots)");
  RunRecord record{runner,
                   r,
                   stats,
                   events,
                   first,
                   {},
                   p.output.energy ? &energy : nullptr,
                   reference ? &*reference : nullptr,
                   p.statistics.episode_resolution};
  for (const auto& c : contacts)
    record.contacts.push_back(c.get());
  record.assessments = assess_windows(p, record);
  record.inputs = p.inputs;
  record.line = &line_windows;
  const ContactStatistics* first_contact = record.first_contact();
  if (first_contact)
    write_contact_force(dir + "/contact_force.csv", contact_force_columns(record));
  Plots plots;
  if (p.output.plots && first_contact)
    plots = draw_plots(dir, p, record);
  if (p.output.report && first_contact)
    write_run_report(dir, record, plots.figures);
  else
    remove_output(dir + "/report.html"); // no report of an earlier run
  // Last: a summary.json that says completed vouches for every file above.
  write_run_summary(dir + "/summary.json", record);
  print_run_report(out, record, p.output.verbosity == Verbosity::detailed);
  if (p.output.plots && first_contact && plots.missing())
    out << (gnuplot_available()
                ? "  (some plots were not drawn: nothing to draw, or gnuplot failed on "
                  "a .gp script in the directory)\n"
                : "  (gnuplot not found: wrote the .gp scripts without PNG plots)\n");
  timer.leave_subsection();
  out << "  wrote time_series.csv" << (first_contact ? ", contact_force.csv" : "")
      << ", summary.json" << (p.output.report && first_contact ? ", report.html" : "");
  for (const std::string& file : plots.drawn)
    if (file.size() > 4 && file.compare(file.size() - 4, 4, ".png") == 0)
      out << ", " << file;
  out << (vtu ? ", solution.pvd with " + std::to_string(vtu->frames().size()) +
                    " frames in vtu/"
              : "")
      << " to " << dir << '\n';
  if (p.output.verbosity == Verbosity::detailed)
    list_files(out, dir);
  if (p.output.verbosity == Verbosity::detailed)
    timer.print_summary();
}
} // namespace pantocat
