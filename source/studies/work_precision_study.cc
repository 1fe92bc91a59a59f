#include <pantocat/base/input_error.h>
#include <pantocat/base/safe_files.h>
#include <pantocat/io/log_log_plot.h>
#include <pantocat/studies/run_distribution.h>
#include <pantocat/studies/work_precision_study.h>

#include <algorithm>
#include <iomanip>
#include <sstream>

namespace pantocat
{
namespace
{
/// The curve called @p title (appended if new).
LogLogCurve& curve(std::vector<LogLogCurve>& curves, const std::string& title)
{
  for (auto& c : curves)
    if (c.title == title)
      return c;
  curves.push_back({title, {}});
  return curves.back();
}
} // namespace

WorkPrecisionStudy::WorkPrecisionStudy(const StudyCase& p) : parameters(p), plan_(p)
{
  require(p.study.reference == StudyReference::separate_run, "Study/Reference",
          "finest run",
          "Mode = work precision compares methods against one separate run: set "
          "Reference = separate run and its discretisation, N+1 and time step");
}

void WorkPrecisionStudy::run()
{
  check_study_grids(plan_.runs(), parameters);
  const RunDistribution distribution;
  root = distribution.is_root();
  const std::vector<RunOutcome> outcomes = distribution.run_and_gather(
      plan_.runs().size(), [&](const unsigned int k)
      { return execute_study_run(plan_.runs()[k], parameters, RunRequest()); });
  if (!root)
    return;
  const RunOutcome& ref = outcomes.back();
  if (ref.status != RunOutcome::Status::completed)
    throw SimulationError("reference run " + plan_.runs().back().label() + " " +
                          to_string(ref.status) + ": " + ref.message);
  reference_peak = *std::max_element(ref.lambda_p.begin(), ref.lambda_p.end());
  reference_cpu = ref.cpu_seconds;
  rows_.clear();
  for (std::size_t k = 0; k + 1 < outcomes.size(); ++k)
  {
    const RunOutcome& o = outcomes[k];
    Row row;
    row.run = plan_.runs()[k];
    row.status = o.status;
    row.message = o.message;
    row.cpu_seconds = o.cpu_seconds;
    row.steps = o.steps;
    if (o.status == RunOutcome::Status::completed)
      row.lambda_p = compare_series(o.t, o.lambda_p, ref.t, ref.lambda_p);
    rows_.push_back(row);
  }
}

std::string WorkPrecisionStudy::curve_title(const StudyRun& run) const
{
  bool several_grids = false;
  for (const auto& r : plan_.runs())
    several_grids = several_grids || (!r.reference && r.n_intervals != run.n_intervals);
  return several_grids ? run.method() + ", N+1 = " + std::to_string(run.n_intervals)
                       : run.method();
}

void WorkPrecisionStudy::write(std::ostream& out) const
{
  if (!root)
    return;
  const std::string name = parameters.study.output_name.empty()
                               ? "work_precision"
                               : parameters.study.output_name;
  const std::string dir = parameters.output.directory;
  const double target = parameters.study.target_relative_error;
  std::ostringstream csv;
  csv << "discretisation,integrator,contact_law,n_intervals,parameter,error_l2,error_max,"
         "relative_error_max,relative_error_peak,cpu_seconds,steps,status\n";
  out << "Errors in lambda_p against " << plan_.runs().back().label()
      << " (max lambda_p = " << std::setprecision(6) << reference_peak << " N, "
      << std::setprecision(3) << reference_cpu << " s CPU)\n"
      << std::left << std::setw(22) << "method" << std::right << std::setw(7) << "N+1"
      << std::setw(11) << "dt [s]" << std::setw(12) << "L2 [N]" << std::setw(12)
      << "max [N]" << std::setw(10) << "max rel" << std::setw(10) << "peak rel"
      << std::setw(10) << "CPU [s]" << '\n';
  bool interpolated = false;
  std::vector<LogLogCurve> curves, peak_curves;
  for (unsigned int m = 0; m < plan_.n_methods(); ++m)
  {
    const std::string method = plan_.runs()[plan_.index(m, 0)].method();
    const Row* cheapest_max = nullptr;
    const Row* cheapest_peak = nullptr;
    for (unsigned int k = 0; k < plan_.n_refinements(); ++k)
    {
      const Row& r = rows_[plan_.index(m, k)];
      csv << to_string(r.run.discretisation) << ',' << r.run.integrator << ','
          << r.run.contact_law_in(parameters) << ',' << r.run.n_intervals << ','
          << std::setprecision(6) << r.run.time_step;
      out << std::left << std::setw(22) << method << std::right << std::setw(7)
          << r.run.n_intervals << std::setw(11) << std::setprecision(3)
          << r.run.time_step;
      if (r.status != RunOutcome::Status::completed)
      {
        csv << ",,,,,," << 0 << ',' << to_string(r.status) << '\n';
        out << "  " << to_string(r.status) << ": " << r.message << '\n';
        continue;
      }
      const SeriesErrors& e = r.lambda_p;
      interpolated = interpolated || e.interpolated;
      csv << std::setprecision(6) << ',' << e.l2 << ',' << e.max << ',' << e.relative_max
          << ',' << e.relative_peak << ',' << std::setprecision(4) << r.cpu_seconds << ','
          << r.steps << ",completed\n";
      out << std::setprecision(3) << std::setw(12) << e.l2 << std::setw(12) << e.max
          << std::setw(10) << e.relative_max << std::setw(10) << e.relative_peak
          << std::setw(10) << r.cpu_seconds << '\n';
      const std::string title = curve_title(r.run);
      curve(curves, title).points.emplace_back(r.cpu_seconds, e.relative_max);
      curve(peak_curves, title).points.emplace_back(r.cpu_seconds, e.relative_peak);
      if (e.relative_max <= target &&
          (!cheapest_max || r.cpu_seconds < cheapest_max->cpu_seconds))
        cheapest_max = &r;
      if (e.relative_peak <= target &&
          (!cheapest_peak || r.cpu_seconds < cheapest_peak->cpu_seconds))
        cheapest_peak = &r;
    }
    const auto report = [&](const char* what, const Row* r)
    {
      out << "  " << method << ": cheapest run with " << what << " <= " << target << ": ";
      if (r)
        out << "N+1 = " << r->run.n_intervals << ", dt = " << r->run.time_step << " s, "
            << std::setprecision(3) << r->cpu_seconds << " s CPU\n";
      else
        out << "none\n";
    };
    report("relative max-norm error of lambda_p", cheapest_max);
    report("relative error of max lambda_p", cheapest_peak);
  }
  if (interpolated)
    out << "  (the reference's step does not divide every run's step: lambda_p_ref "
           "interpolated linearly in time)\n";
  write_file_atomically(dir + "/" + name + ".csv", csv.str());
  out << "  wrote " << name << ".csv";
  if (parameters.output.plots)
  {
    for (auto* list : {&curves, &peak_curves})
      for (auto& curve : *list)
        std::sort(curve.points.begin(), curve.points.end()); // by CPU time
    const bool a =
        plot_log_log(dir, name, "Work precision: lambda_p, max norm", "CPU time [s]",
                     "relative max-norm error of lambda_p", curves, target);
    const bool b =
        plot_log_log(dir, name + "_peak", "Work precision: max lambda_p", "CPU time [s]",
                     "relative error of max lambda_p", peak_curves, target);
    out << (a && b ? ", " + name + ".png, " + name + "_peak.png"
                   : std::string(" (gnuplot not found: no PNG)"));
  }
  out << " to " << dir << '\n';
}

void run_work_precision_study(const StudyCase& parameters, std::ostream& out)
{
  WorkPrecisionStudy study(parameters);
  const RunDistribution distribution;
  if (distribution.is_root())
    out << "Work-precision study: " << study.plan().runs().size() << " runs on "
        << distribution.size() << (distribution.size() == 1 ? " process" : " MPI ranks")
        << '\n';
  study.run();
  study.write(out);
}
} // namespace pantocat
