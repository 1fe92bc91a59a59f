#pragma once

#include <pantocat/studies/contact_figures.h>
#include <pantocat/studies/study_run.h>

#include <limits>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace pantocat
{
/// How the switch events of two runs compare (compare_event_times()).
struct EventTimeDifference
{
  /// Every constraint compared switches as often, and the same way, in both runs.
  bool match = true;
  unsigned long count_a = 0, count_b = 0; ///< events compared in each run
  /// max |t_i(a) - t_i(b)| over the matched events [s]; 0 without events, NaN
  /// if they do not match.
  double max_difference = 0.;
};

/**
 * Matches the switch events of two runs constraint by constraint, each
 * constraint's events in time order: if every constraint has the same
 * sequence of switches (closing, opening) in @p a as in @p b, the largest
 * |t_i(a) - t_i(b)| of its i-th events over all constraints (differences
 * below 1e-12 s, the rounding of t = n dt, count as 0); otherwise no match. Matching per
 * constraint keeps two nearly simultaneous switches of different constraints from being
 * paired crosswise when their order flips.
 * @p only_constraint: compare that constraint's events alone (e.g. a contact's).
 */
EventTimeDifference compare_event_times(const std::vector<StudyEvent>& a,
                                        const std::vector<StudyEvent>& b,
                                        std::optional<unsigned int> only_constraint = {});

/**
 * d_k = |x_k - x_{k+1}| of successive runs (k = 0 .. n-2); NaN where either
 * value is not finite.
 */
std::vector<double> successive_differences(const std::vector<double>& x);

/**
 * The contact statistics of one method (discretisation, integrator, contact
 * law) over its refinements, coarse to fine: per run the ContactFigures, and
 * between successive runs the differences |x(s_{k-1}) - x(s_k)| with the
 * observed order log(d_{k-1} / d_k) / log(s_{k-2} / s_{k-1}) (log2 for a
 * halving) of the contact loss, the filtered max, min and std, and of the
 * event times (pantograph 1's contact, and all constraints) where the events
 * match. Vectors are indexed by run; differences and orders belong to the
 * finer run of each pair (entry 0 is NaN, orders from entry 2).
 */
class ContactConvergence
{
public:
  /// One run of the method.
  struct Run
  {
    StudyRun run;
    std::string contact_law; ///< the law in force (StudyRun::contact_law_in())
    RunOutcome::Status status = RunOutcome::Status::completed;
    std::string message;
    ContactFigures figures; ///< if completed
  };

  /// A quantity, its value per run, its successive differences and orders.
  struct Quantity
  {
    std::string heading; ///< for the text table, with its unit
    std::string csv;     ///< column name
    std::vector<double> values, differences, orders;
  };

  /**
   * @p runs coarse to fine; @p parameters the refinement parameter of each
   * (dt, or h = L/(N+1) when N+1 changes).
   */
  ContactConvergence(std::vector<Run> runs, std::vector<double> parameters);

  const std::vector<Run>& runs() const { return runs_; }
  /// Contact loss, filtered max, min and std.
  const std::vector<Quantity>& quantities() const { return quantities_; }
  /// Event times of pantograph 1's contact between run k-1 and run k (entry 0 unused).
  const std::vector<EventTimeDifference>& contact_event_times() const
  {
    return contact_events;
  }
  /// Event times of every constraint between run k-1 and run k (entry 0 unused).
  const std::vector<EventTimeDifference>& event_times() const { return all_events; }
  /// Observed orders of the max differences of the contact's / all event times.
  const std::vector<double>& contact_event_orders() const { return contact_orders; }
  const std::vector<double>& event_orders() const { return all_orders; }
  /// The completed run with the smallest unilateral force, or nullptr if none completed.
  const Run* smallest_unilateral_force() const;

  /// The per-run table and the table of differences and orders.
  void write_text(std::ostream& out, bool refines_space) const;
  /// The CSV header line of write_csv().
  static std::string csv_header();
  /// One CSV line per run.
  void write_csv(std::ostream& out) const;

private:
  /// Differences, orders and event comparisons from the runs' figures.
  void compare_runs();

  std::vector<Run> runs_;
  std::vector<double> parameters;
  std::vector<Quantity> quantities_;
  std::vector<EventTimeDifference> contact_events, all_events;
  std::vector<double> contact_orders, all_orders;
};
} // namespace pantocat
