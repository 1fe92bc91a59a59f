#pragma once

#include <pantocat/simulation/assessment.h>
#include <pantocat/simulation/checkpoint_parameters.h>
#include <pantocat/studies/sweep_parameters.h>
#include <pantocat/studies/sweep_run.h>

#include <functional>
#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace pantocat
{
class RunDistribution;

/// Which study a sweep is.
enum class SweepKind
{
  speed,      ///< Mode = speed sweep: one run per speed
  parameter,  ///< Mode = parameter sweep: one run per value (or pair of values)
  monte_carlo ///< Mode = monte carlo: one run per sample of installation deviations
};

/**
 * The runs of a sweep: the names of the key columns that identify a run
 * (speed_kmh; the swept entries; sample) and, per run, their values as
 * printed, with an estimate of its cost (to hand out the longest runs first).
 */
struct SweepPlan
{
  SweepKind kind = SweepKind::speed;
  std::vector<std::string> key_columns;
  std::vector<std::vector<std::string>> keys; ///< per run, one value per key column
  std::vector<double> costs;                  ///< per run, any unit (e.g. steps x N+1)
  std::vector<unsigned int> pantographs;      ///< per run, the number of pantographs
  /**
   * Every parameter the runs are made from, as resolved ("Subsection/Entry",
   * value): what decides the rows. A partial file of other parameters is not
   * resumed.
   */
  ParameterFingerprint parameters;

  unsigned int size() const { return keys.size(); }
};

/// The statistic columns of a sweep's CSV, after the key columns and "pantograph".
const std::vector<std::string>& sweep_statistic_columns();

/// The header line of a sweep's CSV (with its newline): @p key_columns, pantograph, the
/// statistics, status, reason.
std::string sweep_csv_header(const std::vector<std::string>& key_columns);

/**
 * The rows of run @p key with @p outcome: one per pantograph in contact
 * (@p n_pantographs rows without figures if it failed or was refused), key
 * values, pantograph, the raw figures, the steady-arm uplift, the filtered
 * figures (empty fields without a cut-off), status and reason (quoted).
 * Numbers with 7 significant digits; NaN (no time point in the window) empty.
 */
std::string sweep_rows(const std::vector<std::string>& key, const SweepOutcome& outcome,
                       unsigned int n_pantographs);

/**
 * Removes from @p directory the results a completed sweep named @p name
 * writes, and those of the default names speed_sweep, parameter_sweep and
 * monte_carlo: <name>.csv, <name>_runs.csv, <name>_distribution.csv,
 * <name>_report.html and the plots <name>[_<statistic>][_pantograph_<k>].png
 * (and .svg) with their .gp scripts.
 * Partial files stay. A file that cannot be removed throws
 * (std::filesystem::filesystem_error names it and why).
 */
void remove_sweep_results(const std::string& directory, const std::string& name);

/// Percentile @p p in [0, 100] of @p sorted (linear between order statistics).
double percentile(const std::vector<double>& sorted, double p);

/**
 * A speed sweep, a parameter sweep or a Monte Carlo study: the runs of
 * @p plan, each made by @p make_run (on the rank that runs it) and run by
 * the CaseRunner, spread over the MPI ranks with a work queue on rank 0
 * (RunDistribution::run_queue). Rank 0 starts <name>.csv.partial with the
 * program version and the plan's parameters (partial_file_start()), removes
 * the results of an earlier sweep (remove_sweep_results()), appends every
 * finished run's record at once (partial_record()) and prints a progress
 * line (runs done / total, time left); with Sweep/Resume it keeps the
 * finished runs of that file (read_partial_file(): a partial file of other
 * parameters or a damaged one is refused) and runs only the others. At the
 * end it writes <name>.csv (rows in plan order: the same file on any number
 * of ranks), <name>_runs.csv (wall time, steps, rank per run), the plots,
 * for Monte Carlo <name>_distribution.csv, and <name>_report.html, and
 * removes the partial file last.
 */
class SweepStudy
{
public:
  struct Output
  {
    std::string directory = "output";
    bool plots = true;
    /// Contact-wire wave speed c [m/s] for the 0.7 c line of the speed plot (0: none).
    double wave_speed = 0.;
    /// <name>_report.html (sweep_report.h), with the limits of @p criteria.
    bool report = true;
    AssessmentCriteria criteria = {};
    double speed = 0.;            ///< [m/s] the base case's (all but speed sweeps)
    double filter_cutoff_hz = 0.; ///< Statistics/Low pass cut-off of the runs (0: raw)
    std::string key_unit; ///< unit of a parameter sweep's first entry ("N"; "": none)
  };

  SweepStudy(SweepPlan plan, std::function<SweepCase(unsigned int)> make_run,
             const SweepParameters& parameters, Output output);

  /// Runs the study (every rank must call it); rank 0 writes the files.
  void run(std::ostream& out);

  /// File base name: Sweep/Output name or speed_sweep | parameter_sweep | monte_carlo.
  std::string name() const;

private:
  /// The rows of runs that a stopped sweep finished (Resume = true), by run index.
  void read_partial();
  /// Rank 0: the partial file read (Resume) or started, earlier results removed.
  void start();
  /// start() on rank 0; its refusal or failure thrown on every rank.
  void start_on_every_rank(const RunDistribution& distribution);
  /// Rank 0: records run @p k's outcome, appends its rows, prints progress.
  void finished(unsigned int k, const SweepOutcome& outcome, std::ostream& out);
  /// Rank 0: <name>.csv, <name>_runs.csv, the distribution and the plots.
  void write(std::ostream& out) const;
  std::string header() const;
  std::string partial_file() const;
  /// Appends @p text to the partial file (one write) and flushes it.
  void append_to_partial(const std::string& text) const;

  SweepPlan plan;
  std::function<SweepCase(unsigned int)> make_run;
  SweepParameters parameters;
  Output output;
  std::map<unsigned int, std::string> rows;    ///< per finished run, its CSV rows
  std::map<unsigned int, std::string> timings; ///< per run run here, its _runs.csv row
  unsigned int done_here = 0, to_run = 0;
  unsigned int dropped_lines = 0; ///< of the partial file, cut short by a stop
  double started = 0.;            ///< wall clock [s] when the runs began
};
} // namespace pantocat
