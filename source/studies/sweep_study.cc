#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>
#include <pantocat/base/safe_files.h>
#include <pantocat/studies/run_distribution.h>
#include <pantocat/studies/sweep_partial.h>
#include <pantocat/studies/sweep_plots.h>
#include <pantocat/studies/sweep_report.h>
#include <pantocat/studies/sweep_study.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <numeric>
#include <set>
#include <sstream>

namespace pantocat
{
namespace
{
double wall_clock()
{
  return std::chrono::duration<double>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

/// The seven figures in the CSV's order.
std::vector<double> in_column_order(const ForceFigures& f)
{
  return {f.mean, f.std, f.mean_minus_3std,     f.mean_plus_3std,
          f.max,  f.min, f.contact_loss_percent};
}

/// @p text as a quoted CSV field on one line.
std::string quoted(const std::string& text)
{
  std::string q = "\"";
  for (const char c : text)
    q +=
        c == '"' ? std::string("\"\"") : std::string(1, c == '\n' || c == '\r' ? ' ' : c);
  return q + "\"";
}

/// "1 min 20 s", "35 s", "2 h 5 min".
std::string duration(const double seconds)
{
  const long s = std::lround(seconds);
  std::ostringstream d;
  if (s >= 3600)
    d << s / 3600 << " h " << (s % 3600) / 60 << " min";
  else if (s >= 60)
    d << s / 60 << " min " << s % 60 << " s";
  else
    d << s << " s";
  return d.str();
}

/// @p text without its first @p n comma-separated fields on each line.
std::string without_keys(const std::string& text, const std::size_t n)
{
  std::string rest;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);)
  {
    std::size_t begin = 0;
    for (std::size_t i = 0; i < n; ++i)
      begin = line.find(',', begin) + 1;
    rest += line.substr(begin) + "\n";
  }
  return rest;
}

/**
 * True if @p file is what a sweep named @p name writes when it completes:
 * <name>.csv, <name>_runs.csv, <name>_distribution.csv, <name>_report.html,
 * or a plot <name>[_<statistic>][_pantograph_<k>] with extension .png, .svg
 * or .gp.
 */
bool is_sweep_result(const std::string& file, const std::string& name)
{
  if (file.rfind(name, 0) != 0)
    return false;
  std::string rest = file.substr(name.size());
  if (rest == ".csv" || rest == "_runs.csv" || rest == "_distribution.csv" ||
      rest == "_report.html")
    return true;
  const auto ends_with = [&](const std::string& end)
  {
    return rest.size() >= end.size() &&
           rest.compare(rest.size() - end.size(), end.size(), end) == 0;
  };
  if (!ends_with(".png") && !ends_with(".svg") && !ends_with(".gp"))
    return false;
  rest.erase(rest.rfind('.'));
  const std::string pantograph = "_pantograph_";
  const std::size_t p = rest.rfind(pantograph);
  if (p != std::string::npos && p + pantograph.size() < rest.size() &&
      rest.find_first_not_of("0123456789", p + pantograph.size()) == std::string::npos)
    rest.erase(p);
  if (rest.empty())
    return true;
  const std::vector<std::string>& statistics = sweep_statistic_columns();
  return std::find(statistics.begin(), statistics.end(), rest.substr(1)) !=
             statistics.end() &&
         rest[0] == '_';
}

/**
 * The swept entries (key columns) of a parameter sweep whose every value gave
 * the same rows, all figures to their printed digits, with the other entry
 * fixed: the runs may not read them (another integrator's setting, an absent
 * pantograph's). Needs two values or more and two completed runs that differ
 * only in that entry.
 */
std::vector<unsigned int>
entries_without_effect(const SweepPlan& plan,
                       const std::map<unsigned int, std::string>& rows)
{
  std::vector<unsigned int> found;
  const std::size_t n_keys = plan.key_columns.size();
  for (unsigned int e = 0; plan.kind == SweepKind::parameter && e < n_keys; ++e)
  {
    std::map<std::string, std::set<std::string>> outcomes; // other entry's value -> rows
    std::map<std::string, unsigned int> n_runs;
    for (const auto& [k, text] : rows)
      if (text.find(",completed,\"\"\n") != std::string::npos)
      {
        const std::string other = n_keys > 1 ? plan.keys[k][1 - e] : "";
        outcomes[other].insert(without_keys(text, n_keys));
        ++n_runs[other];
      }
    bool same = !outcomes.empty(), compared = false;
    for (const auto& [other, distinct] : outcomes)
      same = same && distinct.size() == 1, compared = compared || n_runs[other] > 1;
    if (same && compared)
      found.push_back(e);
  }
  return found;
}

/// A short account of run @p outcome for the progress line.
std::string account(const SweepOutcome& outcome)
{
  std::ostringstream a;
  if (outcome.status != SweepOutcome::Status::completed)
    return std::string(to_string(outcome.status)) + ": " + outcome.reason;
  for (const PantographFigures& p : outcome.pantographs)
  {
    const ForceFigures& f = p.has_filtered ? p.filtered : p.raw;
    a << (p.number > 1 ? "; " : "") << "pantograph " << p.number << ": sigma "
      << std::fixed << std::setprecision(1) << f.std << " N"
      << (p.has_filtered ? " (filtered)" : "") << ", loss " << std::setprecision(2)
      << p.raw.contact_loss_percent << " %";
  }
  return a.str();
}
} // namespace

const std::vector<std::string>& sweep_statistic_columns()
{
  static const std::vector<std::string> columns = {"mean",
                                                   "std",
                                                   "mean_minus_3std",
                                                   "mean_plus_3std",
                                                   "max",
                                                   "min",
                                                   "contact_loss_percent",
                                                   "max_support_uplift_m",
                                                   "filtered_mean",
                                                   "filtered_std",
                                                   "filtered_mean_minus_3std",
                                                   "filtered_mean_plus_3std",
                                                   "filtered_max",
                                                   "filtered_min",
                                                   "filtered_contact_loss_percent"};
  return columns;
}

std::string sweep_csv_header(const std::vector<std::string>& key_columns)
{
  std::string h;
  for (const std::string& k : key_columns)
    h += k + ",";
  h += "pantograph";
  for (const std::string& c : sweep_statistic_columns())
    h += "," + c;
  return h + ",status,reason\n";
}

void remove_sweep_results(const std::string& directory, const std::string& name)
{
  namespace fs = std::filesystem;
  std::vector<fs::path> earlier;
  const std::vector<std::string> names = {name, "speed_sweep", "parameter_sweep",
                                          "monte_carlo"};
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(directory, error))
  {
    const std::string file = entry.path().filename().string();
    if (file == "summary.json" ||
        std::any_of(names.begin(), names.end(),
                    [&](const std::string& n) { return is_sweep_result(file, n); }))
      earlier.push_back(entry.path());
  }
  if (error)
    throw SimulationError("cannot list " + directory + ": " + error.message());
  for (const fs::path& file : earlier)
    if (!fs::remove(file, error) && error)
      throw SimulationError("cannot remove " + file.string() +
                            ", a result of an earlier run: " + error.message());
}

std::string sweep_rows(const std::vector<std::string>& key, const SweepOutcome& outcome,
                       const unsigned int n_pantographs)
{
  std::string keys;
  for (const std::string& k : key)
    keys += k + ",";
  std::string text;
  const std::string end =
      std::string(to_string(outcome.status)) + "," + quoted(outcome.reason) + "\n";
  if (outcome.status != SweepOutcome::Status::completed || outcome.pantographs.empty())
  {
    const std::string empty(sweep_statistic_columns().size(), ',');
    for (unsigned int p = 1; p <= std::max(n_pantographs, 1u); ++p)
      text += keys + std::to_string(p) + empty + "," + end;
    return text;
  }
  for (const PantographFigures& p : outcome.pantographs)
  {
    text += keys + std::to_string(p.number);
    for (const double x : in_column_order(p.raw))
      text += "," + csv_field(x);
    text += "," + (p.has_uplift ? csv_field(p.max_steady_arm_uplift) : std::string());
    for (const double x : in_column_order(p.filtered))
      text += "," + (p.has_filtered ? csv_field(x) : std::string());
    text += "," + end;
  }
  return text;
}

double percentile(const std::vector<double>& sorted, const double p)
{
  if (sorted.empty())
    return std::nan("");
  const double position = p / 100. * (sorted.size() - 1);
  const std::size_t below = static_cast<std::size_t>(std::floor(position));
  const std::size_t above = std::min(below + 1, sorted.size() - 1);
  return sorted[below] + (position - below) * (sorted[above] - sorted[below]);
}

SweepStudy::SweepStudy(SweepPlan plan, std::function<SweepCase(unsigned int)> make_run,
                       const SweepParameters& parameters, Output output)
    : plan(std::move(plan)), make_run(std::move(make_run)), parameters(parameters),
      output(std::move(output))
{
}

std::string SweepStudy::name() const
{
  if (!parameters.output_name.empty())
    return parameters.output_name;
  return plan.kind == SweepKind::speed       ? "speed_sweep"
         : plan.kind == SweepKind::parameter ? "parameter_sweep"
                                             : "monte_carlo";
}

std::string SweepStudy::header() const
{
  return sweep_csv_header(plan.key_columns);
}

std::string SweepStudy::partial_file() const
{
  return output.directory + "/" + name() + ".csv.partial";
}

void SweepStudy::read_partial()
{
  const std::string file = partial_file();
  // Not through a link, not a FIFO or device (refused without reading it).
  const FileContent content = read_regular_file(file, std::uint64_t(1) << 30, false);
  require(!content.missing, "Sweep/Resume", "true",
          "there is no " + file +
              " to resume from (a completed sweep removes it); "
              "allowed: Resume = false to start the sweep");
  require(content.bytes.has_value(), "Sweep/Resume", "true",
          file + " " + content.problem + "; allowed: Resume = false to start the sweep");
  PartialRuns finished = read_partial_file(*content.bytes, file, plan);
  rows = std::move(finished.rows);
  dropped_lines = finished.dropped_lines;
}

void SweepStudy::start()
{
  if (parameters.resume)
    read_partial();
  remove_sweep_results(output.directory, name());
  // Resumed: the finished runs again, without what a stop cut short.
  std::string text = partial_file_start(plan);
  for (const auto& [k, text_of_run] : rows)
    text += partial_record(text_of_run);
  write_file_atomically(partial_file(), text);
}

void SweepStudy::append_to_partial(const std::string& text) const
{
  OutputFile partial(partial_file(), OutputFile::Append{});
  partial << text;
  partial.close();
}

void SweepStudy::finished(const unsigned int k, const SweepOutcome& outcome,
                          std::ostream& out)
{
  rows[k] = sweep_rows(plan.keys[k], outcome, plan.pantographs[k]);
  append_to_partial(partial_record(rows[k]));
  std::ostringstream timing;
  for (const std::string& key : plan.keys[k])
    timing << key << ",";
  timing << to_string(outcome.status) << "," << std::setprecision(4)
         << outcome.wall_seconds << "," << outcome.cpu_seconds << "," << outcome.steps
         << "," << outcome.rank << "\n";
  timings[k] = timing.str();
  ++done_here;
  const double elapsed = wall_clock() - started;
  const unsigned int left = to_run - done_here;
  out << "  [" << rows.size() << "/" << plan.size() << "] ";
  for (unsigned int c = 0; c < plan.key_columns.size(); ++c)
    out << (c ? ", " : "") << plan.key_columns[c] << " = " << plan.keys[k][c];
  out << ": " << account(outcome) << " (" << std::fixed << std::setprecision(1)
      << outcome.wall_seconds << " s on rank " << outcome.rank << ")"
      << std::defaultfloat;
  if (left > 0)
    out << "; about " << duration(elapsed / done_here * left) << " left";
  out << std::endl;
}

void SweepStudy::start_on_every_rank(const RunDistribution& distribution)
{
  // Rank 0 reads (or starts) the partial file; a refusal there must stop
  // every rank, not leave the others waiting for runs. The first character
  // says which: 'i' bad input (InputError), 's' a file that cannot be changed.
  std::string refusal;
  if (distribution.is_root())
    try
    {
      start();
    }
    catch (const InputError& e)
    {
      refusal = std::string("i") + e.what();
    }
    catch (const SimulationError& e)
    {
      refusal = std::string("s") + e.what();
    }
  if (distribution.size() > 1)
    refusal = dealii::Utilities::MPI::broadcast(MPI_COMM_WORLD, refusal, 0);
  if (!refusal.empty() && refusal[0] == 'i')
    throw InputError(refusal.substr(1));
  if (!refusal.empty())
    throw SimulationError(refusal.substr(1));
}

void SweepStudy::run(std::ostream& out)
{
  const RunDistribution distribution;
  const bool root = distribution.is_root();
  start_on_every_rank(distribution);
  std::vector<unsigned int> order;
  for (unsigned int k = 0; k < plan.size(); ++k)
    if (!rows.count(k))
      order.push_back(k);
  // Longest runs first: the last runs to finish are then short ones.
  std::stable_sort(order.begin(), order.end(),
                   [&](const unsigned int a, const unsigned int b)
                   { return plan.costs[a] > plan.costs[b]; });
  // Sweep/Stop after runs (tests): the first runs only, then stop as if killed.
  bool stops =
      parameters.stop_after_runs > 0 && parameters.stop_after_runs < order.size();
  if (stops)
    order.resize(parameters.stop_after_runs);
  to_run = order.size();
  if (root)
    out << name() << ": " << plan.size() << " runs on " << distribution.size()
        << (distribution.size() == 1 ? " process" : " MPI ranks (dynamic work queue)")
        << (rows.empty() && !parameters.resume
                ? ""
                : ", " + std::to_string(rows.size()) + " finished before (Resume = true" +
                      (dropped_lines > 0 ? "; " + std::to_string(dropped_lines) +
                                               " lines of a run cut short dropped)"
                                         : ")"))
        << std::endl;
  started = wall_clock();
  const auto execute = [&](const unsigned int k, const std::function<void()>& poll)
  {
    SweepOutcome outcome;
    try
    {
      outcome = execute_sweep_run(make_run(k), poll);
    }
    catch (const std::exception& e) // a run's case refused while made: its row says why
    {
      outcome.status = dynamic_cast<const InputError*>(&e) ? SweepOutcome::Status::refused
                                                           : SweepOutcome::Status::failed;
      outcome.reason = e.what();
    }
    outcome.rank = distribution.rank();
    return outcome.pack();
  };
  // Only rank 0's order matters (it hands out the runs); the others get the same.
  distribution.run_queue(order, execute,
                         [&](const unsigned int k, const std::vector<char>& bytes)
                         { finished(k, SweepOutcome::unpack(bytes), out); });
  if (distribution.size() > 1)
    stops = dealii::Utilities::MPI::broadcast(MPI_COMM_WORLD, stops, 0);
  if (stops)
    throw SimulationError("stopped after " + std::to_string(parameters.stop_after_runs) +
                          " runs as asked (Sweep/Stop after runs); " + partial_file() +
                          " holds them: Sweep/Resume = true runs the others");
  if (root)
    write(out);
}

void SweepStudy::write(std::ostream& out) const
{
  const std::string dir = output.directory;
  std::string csv = header();
  for (const auto& [k, text] : rows)
    csv += text;
  write_file_atomically(dir + "/" + name() + ".csv", csv);
  std::string runs;
  for (const std::string& k : plan.key_columns)
    runs += k + ",";
  runs += "status,wall_seconds,cpu_seconds,steps,rank\n";
  for (const auto& [k, text] : timings)
    runs += text;
  write_file_atomically(dir + "/" + name() + "_runs.csv", runs);
  const SweepTable table = read_sweep_table(csv, plan.key_columns.size());
  if (plan.kind == SweepKind::monte_carlo)
  {
    write_file_atomically(dir + "/" + name() + "_distribution.csv",
                          monte_carlo_distribution_csv(table));
    print_monte_carlo_summary(out, table);
  }
  out << "  wrote " << name() << ".csv, " << name() << "_runs.csv";
  if (plan.kind == SweepKind::monte_carlo)
    out << ", " << name() << "_distribution.csv";
  std::vector<std::string> pictures; // SVG copies for the report
  if (output.plots)
  {
    const std::vector<std::string> drawn =
        plot_sweep(dir, name(), plan.kind, table, output.wave_speed,
                   output.criteria.enabled ? &output.criteria : nullptr, output.key_unit);
    for (const std::string& file : drawn)
      (file.size() > 4 && file.compare(file.size() - 4, 4, ".svg") == 0
           ? pictures.push_back(file)
           : void(out << ", " << file));
    if (drawn.empty())
      out << " (no plot: gnuplot missing or nothing to draw)";
  }
  if (output.report)
  {
    write_sweep_report(dir, table,
                       {name(), plan.kind, &output.criteria, output.speed,
                        output.filter_cutoff_hz, pictures});
    out << ", " << name() << "_report.html";
  }
  out << " to " << dir << std::endl;
  for (const unsigned int e : entries_without_effect(plan, rows))
    std::cerr << "pantocat-fem: warning: Sweep/"
              << (e == 0 ? "Parameter" : "Second parameter") << " = "
              << plan.key_columns[e]
              << ": every value gave the same figures (every completed row equal to all "
                 "its digits): the runs may not use this entry in this case"
              << std::endl;
  std::filesystem::remove(partial_file()); // last: until here a resume can go on
}
} // namespace pantocat
