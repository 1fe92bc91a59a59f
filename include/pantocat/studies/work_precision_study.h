#pragma once

#include <pantocat/studies/series_comparison.h>
#include <pantocat/studies/study_case.h>
#include <pantocat/studies/study_plan.h>

#include <ostream>
#include <vector>

namespace pantocat
{
/**
 * Mode = work precision: every discretisation x integrator x (N+1, dt) of
 * the Study subsection (paired, or all combinations) against one separate
 * reference run: the error in
 * lambda_p (L2 and max over time, and in max lambda_p) and the CPU time of
 * the run (set-up, 2/omega_max for the half-explicit method, and time loop).
 * Writes <name>.csv (discretisation, integrator, n_intervals, parameter = dt,
 * error_l2, error_max, relative errors, cpu_seconds, status) and plots of the
 * relative error against CPU time, one curve per method. The runs are spread
 * over the MPI ranks; rank 0 writes the results.
 */
class WorkPrecisionStudy
{
public:
  explicit WorkPrecisionStudy(const StudyCase& parameters);

  struct Row
  {
    StudyRun run;
    RunOutcome::Status status = RunOutcome::Status::completed;
    std::string message;
    SeriesErrors lambda_p;
    double cpu_seconds = 0.;
    unsigned long steps = 0;
  };

  /// Runs the study (every rank must call it); on rank 0 computes the rows.
  void run();
  /// All rows in plan order (method-major), reference excluded (rank 0 only).
  const std::vector<Row>& rows() const { return rows_; }
  const StudyPlan& plan() const { return plan_; }
  /// Prints the table and the cheapest runs within the target; writes the files.
  void write(std::ostream& out) const;

private:
  /// One curve per method, or per method and grid if the study has several grids.
  std::string curve_title(const StudyRun& run) const;

  StudyCase parameters;
  StudyPlan plan_;
  std::vector<Row> rows_;
  double reference_peak = 0., reference_cpu = 0.;
  bool root = true;
};

/// Mode = work precision: runs, prints and writes the study (all ranks call it).
void run_work_precision_study(const StudyCase& parameters, std::ostream& out);
} // namespace pantocat
