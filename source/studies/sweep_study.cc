#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>
#include <pantocat/io/atomic_file.h>
#include <pantocat/studies/run_distribution.h>
#include <pantocat/studies/sweep_plots.h>
#include <pantocat/studies/sweep_study.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <numeric>
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

/// The first @p n comma-separated fields of @p line.
std::vector<std::string> first_fields(const std::string& line, const std::size_t n)
{
  std::vector<std::string> fields;
  std::size_t begin = 0;
  while (fields.size() < n && begin <= line.size())
  {
    const std::size_t end = std::min(line.find(',', begin), line.size());
    fields.push_back(line.substr(begin, end - begin));
    begin = end + 1;
  }
  return fields;
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
  std::string h;
  for (const std::string& k : plan.key_columns)
    h += k + ",";
  h += "pantograph";
  for (const std::string& c : sweep_statistic_columns())
    h += "," + c;
  return h + ",status,reason\n";
}

std::string SweepStudy::partial_file() const
{
  return output.directory + "/" + name() + ".csv.partial";
}

void SweepStudy::read_partial()
{
  const std::string file = partial_file();
  std::ifstream in(file);
  require(static_cast<bool>(in), "Sweep/Resume", "true",
          "there is no " + file +
              " to resume from (a completed sweep removes it); "
              "allowed: Resume = false to start the sweep");
  std::string line;
  std::getline(in, line);
  require(line + "\n" == header(), "Sweep/Resume", "true",
          file + " has the columns of another sweep; allowed: Resume = false, or the "
                 "sweep that wrote it");
  std::map<std::vector<std::string>, unsigned int> index;
  for (unsigned int k = 0; k < plan.size(); ++k)
    index[plan.keys[k]] = k;
  const std::string written = [&]
  {
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }();
  // A run's rows are appended with one write: every complete line belongs to
  // a finished run. A last line without its newline was cut when the sweep
  // was killed: that run runs again.
  std::size_t begin = 0;
  while (begin < written.size())
  {
    const std::size_t end = written.find('\n', begin);
    if (end == std::string::npos)
      break;
    line = written.substr(begin, end - begin);
    begin = end + 1;
    const auto key = first_fields(line, plan.key_columns.size());
    const auto k = index.find(key);
    require(k != index.end(), "Sweep/Resume", "true",
            file + " holds a run (" + line.substr(0, line.find(',')) +
                ") that this sweep does not have; allowed: Resume = false, or the "
                "sweep that wrote it");
    rows[k->second] += line + "\n";
  }
  std::string clean = header(); // without a cut last line, to append to
  for (const auto& [k, text] : rows)
    clean += text;
  write_file_atomically(file, clean);
}

void SweepStudy::finished(const unsigned int k, const SweepOutcome& outcome,
                          std::ostream& out)
{
  rows[k] = sweep_rows(plan.keys[k], outcome, plan.pantographs[k]);
  {
    std::ofstream partial(partial_file(), std::ios::app);
    partial << rows[k] << std::flush;
    if (!partial)
      throw SimulationError("cannot append to " + partial_file());
  }
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

void SweepStudy::run(std::ostream& out)
{
  const RunDistribution distribution;
  const bool root = distribution.is_root();
  // Rank 0 reads (or starts) the partial file; a refusal there must stop
  // every rank, not leave the others waiting for runs.
  std::string refusal;
  if (root)
    try
    {
      if (parameters.resume)
        read_partial();
      else
        write_file_atomically(partial_file(), header());
    }
    catch (const InputError& e)
    {
      refusal = e.what();
    }
  if (distribution.size() > 1)
    refusal = dealii::Utilities::MPI::broadcast(MPI_COMM_WORLD, refusal, 0);
  if (!refusal.empty())
    throw InputError(refusal);
  std::vector<unsigned int> order;
  for (unsigned int k = 0; k < plan.size(); ++k)
    if (!rows.count(k))
      order.push_back(k);
  // Longest runs first: the last runs to finish are then short ones.
  std::stable_sort(order.begin(), order.end(),
                   [&](const unsigned int a, const unsigned int b)
                   { return plan.costs[a] > plan.costs[b]; });
  to_run = order.size();
  if (root)
    out << name() << ": " << plan.size() << " runs on " << distribution.size()
        << (distribution.size() == 1 ? " process" : " MPI ranks (dynamic work queue)")
        << (rows.empty()
                ? ""
                : ", " + std::to_string(rows.size()) + " finished before (Resume = true)")
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
  std::filesystem::remove(partial_file());
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
  if (output.plots)
  {
    const std::vector<std::string> drawn =
        plot_sweep(dir, name(), plan.kind, table, output.wave_speed);
    for (const std::string& file : drawn)
      out << ", " << file;
    if (drawn.empty())
      out << " (no plot: gnuplot missing or nothing to draw)";
  }
  out << " to " << dir << std::endl;
}
} // namespace pantocat
