#include <pantocat/base/number_format.h>
#include <pantocat/studies/contact_convergence.h>
#include <pantocat/studies/study_plan.h>

#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>

namespace pantocat
{
namespace
{
constexpr double no_value = std::numeric_limits<double>::quiet_NaN();
/// Event times that differ by less than this [s] are the same time point.
constexpr double rounding = 1e-12;

/// Each compared constraint's events, in time order.
std::map<unsigned int, std::vector<StudyEvent>>
by_constraint(const std::vector<StudyEvent>& events,
              const std::optional<unsigned int> only_constraint, unsigned long& count)
{
  std::map<unsigned int, std::vector<StudyEvent>> lists;
  for (const StudyEvent& e : events)
    if (!only_constraint || e.constraint == *only_constraint)
      lists[e.constraint].push_back(e), ++count;
  return lists;
}

/// The largest |t_i(a) - t_i(b)| of two switch sequences, NaN if they differ.
double max_time_difference(const std::vector<StudyEvent>& a,
                           const std::vector<StudyEvent>& b)
{
  if (a.size() != b.size())
    return no_value;
  double d = 0.;
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    if (a[i].closes != b[i].closes)
      return no_value;
    // Below 1e-12 s a difference is the rounding of t = n dt: none.
    const double t = std::abs(a[i].t - b[i].t);
    d = std::max(d, t < rounding ? 0. : t);
  }
  return d;
}

/// A table cell: @p x in fixed or scientific notation, "-" if not finite.
std::string cell(const double x, const int precision, const bool scientific = false)
{
  if (!std::isfinite(x))
    return "-";
  std::ostringstream s;
  s << (scientific ? std::scientific : std::fixed) << std::setprecision(precision) << x;
  return s.str();
}

/// "3 each, 1.20e-04 s", "no events" or "3 vs 5: counts differ".
std::string describe(const EventTimeDifference& d)
{
  std::ostringstream s;
  if (!d.match)
    s << d.count_a << " vs " << d.count_b
      << (d.count_a == d.count_b ? ": sequences differ" : ": counts differ");
  else if (d.count_a == 0)
    s << "no events";
  else
    s << d.count_a << " each, " << cell(d.max_difference, 2, true) << " s";
  return s.str();
}

/// The refinement step of run @p k: "5.00e-05" (dt) or "500" (N+1).
std::string step_label(const StudyRun& run, const bool refines_space)
{
  return refines_space ? std::to_string(run.n_intervals) : cell(run.time_step, 3, true);
}
} // namespace

EventTimeDifference compare_event_times(const std::vector<StudyEvent>& a,
                                        const std::vector<StudyEvent>& b,
                                        const std::optional<unsigned int> only_constraint)
{
  EventTimeDifference d;
  const auto lists_a = by_constraint(a, only_constraint, d.count_a);
  const auto lists_b = by_constraint(b, only_constraint, d.count_b);
  const std::vector<StudyEvent> none;
  for (const auto* lists : {&lists_a, &lists_b})
    for (const auto& [constraint, list] : *lists)
    {
      const auto in_a = lists_a.find(constraint);
      const auto in_b = lists_b.find(constraint);
      const double t = max_time_difference(in_a == lists_a.end() ? none : in_a->second,
                                           in_b == lists_b.end() ? none : in_b->second);
      if (std::isnan(t))
      {
        d.match = false;
        d.max_difference = no_value;
        return d;
      }
      d.max_difference = std::max(d.max_difference, t);
    }
  return d;
}

std::vector<double> successive_differences(const std::vector<double>& x)
{
  std::vector<double> d;
  for (std::size_t k = 0; k + 1 < x.size(); ++k)
    d.push_back(std::isfinite(x[k]) && std::isfinite(x[k + 1]) ? std::abs(x[k] - x[k + 1])
                                                               : no_value);
  return d;
}

ContactConvergence::ContactConvergence(std::vector<Run> runs,
                                       std::vector<double> parameters)
    : runs_(std::move(runs)), parameters(std::move(parameters))
{
  compare_runs();
}

void ContactConvergence::compare_runs()
{
  const auto completed = [](const Run& r)
  { return r.status == RunOutcome::Status::completed; };
  quantities_ = {{"loss [%]", "loss_percent", {}, {}, {}},
                 {"max filt. [N]", "filtered_max", {}, {}, {}},
                 {"min filt. [N]", "filtered_min", {}, {}, {}},
                 {"std filt. [N]", "filtered_std", {}, {}, {}}};
  for (const Run& r : runs_)
  {
    const ContactFigures& f = r.figures;
    const bool ok = completed(r);
    const double values[4] = {f.loss_percent, f.filtered_max, f.filtered_min,
                              f.filtered_std};
    for (unsigned int q = 0; q < 4; ++q)
      quantities_[q].values.push_back(ok ? values[q] : no_value);
  }
  // Pairs (k-1, k) carry the refinement parameter of their coarser run.
  std::vector<double> pair_parameters(parameters.begin(),
                                      parameters.end() - (parameters.empty() ? 0 : 1));
  const auto by_finer_run = [](std::vector<double> pairs)
  {
    pairs.insert(pairs.begin(), no_value);
    return pairs;
  };
  for (Quantity& q : quantities_)
  {
    const std::vector<double> d = successive_differences(q.values);
    q.differences = by_finer_run(d);
    q.orders = by_finer_run(observed_orders(d, pair_parameters));
  }
  contact_events.assign(runs_.size(), {});
  all_events.assign(runs_.size(), {});
  std::vector<double> contact_d, all_d;
  for (std::size_t k = 1; k < runs_.size(); ++k)
  {
    const Run& a = runs_[k - 1];
    const Run& b = runs_[k];
    if (!completed(a) || !completed(b))
      contact_events[k] = all_events[k] = {false, 0, 0, no_value};
    else
    {
      contact_events[k] =
          compare_event_times(a.figures.events, b.figures.events, a.figures.contact);
      all_events[k] = compare_event_times(a.figures.events, b.figures.events);
    }
    contact_d.push_back(contact_events[k].max_difference);
    all_d.push_back(all_events[k].max_difference);
  }
  contact_orders = by_finer_run(observed_orders(contact_d, pair_parameters));
  all_orders = by_finer_run(observed_orders(all_d, pair_parameters));
}

const ContactConvergence::Run* ContactConvergence::smallest_unilateral_force() const
{
  const Run* smallest = nullptr;
  for (const Run& r : runs_)
    if (r.status == RunOutcome::Status::completed &&
        std::isfinite(r.figures.min_unilateral_force) &&
        (!smallest ||
         r.figures.min_unilateral_force < smallest->figures.min_unilateral_force))
      smallest = &r;
  return smallest;
}

void ContactConvergence::write_text(std::ostream& out, const bool refines_space) const
{
  const char* step = refines_space ? "N+1" : "dt [s]";
  out << "  " << std::setw(10) << step << std::setw(10) << "loss [%]" << std::setw(15)
      << "max filt. [N]" << std::setw(15) << "min filt. [N]" << std::setw(15)
      << "std filt. [N]" << std::setw(17) << "min unilat. [N]"
      << "  " << std::left << std::setw(24) << "(constraint, t [s])" << std::right
      << std::setw(8) << "events" << std::setw(16) << "contact events"
      << "  short episodes [ms]" << '\n';
  for (const Run& r : runs_)
  {
    out << "  " << std::setw(10) << step_label(r.run, refines_space);
    if (r.status != RunOutcome::Status::completed)
    {
      out << "  " << to_string(r.status) << ": " << r.message << '\n';
      continue;
    }
    const ContactFigures& f = r.figures;
    out << std::setw(10) << cell(f.loss_percent, 3) << std::setw(15)
        << cell(f.filtered_max, 3) << std::setw(15) << cell(f.filtered_min, 3)
        << std::setw(15) << cell(f.filtered_std, 3) << std::setw(17)
        << cell(f.min_unilateral_force, 3) << "  " << std::left << std::setw(24)
        << ("(" + f.min_unilateral_constraint + ", " + cell(f.min_unilateral_time, 5) +
            ")")
        << std::right << std::setw(8) << f.events.size() << std::setw(16)
        << f.contact_events() << "  " << f.short_episodes << " ("
        << cell(1e3 * f.short_episode_time, 3) << ")\n";
  }
  out << "  successive differences |x(" << (refines_space ? "N+1" : "dt") << ") - x("
      << (refines_space ? "2(N+1)" : "dt/2")
      << ")| (on the finer run's line) and observed orders log(d_prev/d_this)/"
         "log(ratio) (log2 for a halving):\n";
  out << "  " << std::setw(10) << step;
  for (const Quantity& q : quantities_)
    out << std::setw(15) << q.heading << std::setw(7) << "order";
  out << "  " << std::left << std::setw(34) << "contact events: max |t_i - t'_i|"
      << std::setw(7) << "order" << std::setw(34) << "all events: max |t_i - t'_i|"
      << "order" << std::right << '\n';
  for (std::size_t k = 1; k < runs_.size(); ++k)
  {
    out << "  " << std::setw(10) << step_label(runs_[k].run, refines_space);
    for (const Quantity& q : quantities_)
      out << std::setw(15) << cell(q.differences[k], 3, true) << std::setw(7)
          << cell(q.orders[k], 2);
    // Events of a run that did not complete are not compared.
    const bool compared = runs_[k - 1].status == RunOutcome::Status::completed &&
                          runs_[k].status == RunOutcome::Status::completed;
    out << "  " << std::left << std::setw(34)
        << (compared ? describe(contact_events[k]) : "-") << std::setw(7)
        << cell(contact_orders[k], 2) << std::setw(34)
        << (compared ? describe(all_events[k]) : "-") << cell(all_orders[k], 2)
        << std::right << '\n';
  }
}

std::string ContactConvergence::csv_header()
{
  std::string h = "discretisation,integrator,contact_law,n_intervals,time_step,status,"
                  "loss_percent,filtered_max,filtered_min,filtered_std,"
                  "min_unilateral_force,min_unilateral_constraint,min_unilateral_time,"
                  "events,contact_events,short_episodes,short_episode_time";
  for (const char* q : {"loss_percent", "filtered_max", "filtered_min", "filtered_std"})
    h += std::string(",") + q + "_difference," + q + "_order";
  return h +
         ",contact_events_match,contact_event_time_difference,contact_event_time_order,"
         "events_match,event_time_difference,event_time_order";
}

void ContactConvergence::write_csv(std::ostream& out) const
{
  // Empty on the first line and next to a run that did not complete.
  const auto done = [&](const std::size_t i)
  { return runs_[i].status == RunOutcome::Status::completed; };
  const auto match = [&](const std::size_t k, const EventTimeDifference& d) {
    return k == 0 || !done(k - 1) || !done(k) ? "" : d.match ? "agree" : "differ";
  };
  for (std::size_t k = 0; k < runs_.size(); ++k)
  {
    const Run& r = runs_[k];
    const ContactFigures& f = r.figures;
    const bool ok = r.status == RunOutcome::Status::completed;
    out << to_string(r.run.discretisation) << ',' << r.run.integrator << ','
        << r.contact_law << ',' << r.run.n_intervals << ',' << csv_field(r.run.time_step)
        << ',' << to_string(r.status);
    for (const Quantity& q : quantities_)
      out << ',' << csv_field(q.values[k]);
    out << ',' << csv_field(ok ? f.min_unilateral_force : no_value) << ','
        << (ok ? f.min_unilateral_constraint : "") << ','
        << csv_field(ok ? f.min_unilateral_time : no_value) << ','
        << (ok ? std::to_string(f.events.size()) : "") << ','
        << (ok ? std::to_string(f.contact_events()) : "") << ','
        << (ok ? std::to_string(f.short_episodes) : "") << ','
        << csv_field(ok ? f.short_episode_time : no_value);
    for (const Quantity& q : quantities_)
      out << ',' << csv_field(q.differences[k]) << ',' << csv_field(q.orders[k]);
    out << ',' << match(k, contact_events[k]) << ','
        << csv_field(k == 0 ? no_value : contact_events[k].max_difference) << ','
        << csv_field(contact_orders[k]) << ',' << match(k, all_events[k]) << ','
        << csv_field(k == 0 ? no_value : all_events[k].max_difference) << ','
        << csv_field(all_orders[k]) << '\n';
  }
}
} // namespace pantocat
