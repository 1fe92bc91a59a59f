#pragma once

#include <pantocat/studies/contact_convergence.h>
#include <pantocat/studies/series_comparison.h>
#include <pantocat/studies/study_case.h>
#include <pantocat/studies/study_plan.h>

#include <ostream>
#include <string>
#include <vector>

namespace pantocat
{
/**
 * Mode = convergence study: one case run for a list of refinements (N+1
 * and/or dt) with each chosen method; errors against the finest run or a
 * separate reference run in lambda_p over time (L2, max), the contact wire at
 * the final time (L2, H1) and the lowest eigenfrequency of each wire; observed
 * orders in a deal.II ConvergenceTable (<name>.txt), <name>.csv and log-log
 * plots <name>.png (lambda_p), <name>_wire.png, <name>_frequencies.png. With
 * Quantities = contact statistics, per method the ContactConvergence of its
 * runs (<name>_contact.txt, <name>_contact.csv; no reference needed). The runs
 * are spread over the MPI ranks (RunDistribution); rank 0 writes the results.
 */
class ConvergenceStudy
{
public:
  explicit ConvergenceStudy(const StudyCase& parameters);

  /// One refinement of one method with its errors (NaN where not computed).
  struct Row
  {
    StudyRun run;
    RunOutcome::Status status = RunOutcome::Status::completed;
    std::string message;
    SeriesErrors lambda_p;
    ProfileErrors wire;
    double carrier_frequency_error = 0.; ///< |f_min - f_min,ref| [Hz]
    double contact_wire_frequency_error = 0.;
    double cpu_seconds = 0.;
  };

  /// Runs the study (every rank must call it); on rank 0 computes the rows.
  void run();
  /// Rows of method @p m, coarse to fine, reference excluded (rank 0 only;
  /// empty without the error table).
  const std::vector<Row>& rows(unsigned int m) const { return rows_[m]; }
  /// The contact statistics of method @p m (rank 0, Quantities = contact statistics).
  const ContactConvergence& contact(unsigned int m) const { return contact_[m]; }
  const StudyPlan& plan() const { return plan_; }
  /// Refinement parameter of each row of method @p m: h = L/(N+1) or dt.
  std::vector<double> refinement_parameters(unsigned int m) const;
  /// Refinement parameter of @p run: h = L/(N+1) if N+1 changes, else dt.
  double refinement_parameter(const StudyRun& run) const;

  /// Prints the tables and writes <name>.txt, <name>.csv and the plots, and
  /// the contact tables (rank 0 only).
  void write(std::ostream& out) const;

private:
  /// The error rows of every method from the gathered outcomes.
  void compare_with_references(const std::vector<RunOutcome>& outcomes);
  /// The contact statistics of every method from the gathered outcomes.
  void collect_contact_statistics(const std::vector<RunOutcome>& outcomes);
  /// The error tables, <name>.txt, <name>.csv and the plots.
  void write_errors(std::ostream& out, const std::string& name) const;
  /// The contact tables, <name>_contact.txt and <name>_contact.csv.
  void write_contact_statistics(std::ostream& out, const std::string& name) const;

  StudyCase parameters;
  StudyPlan plan_;
  std::vector<std::vector<Row>> rows_;
  std::vector<ContactConvergence> contact_;
  bool root = true;
};

/// Mode = convergence study: runs, prints and writes the study (all ranks call it).
void run_convergence_study(const StudyCase& parameters, std::ostream& out);
} // namespace pantocat
