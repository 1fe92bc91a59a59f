#include <pantocat/base/input_error.h>
#include <pantocat/base/safe_files.h>
#include <pantocat/io/log_log_plot.h>
#include <pantocat/studies/convergence_study.h>
#include <pantocat/studies/run_distribution.h>

#include <deal.II/base/convergence_table.h>

#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace pantocat
{
namespace
{
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

double value(const ConvergenceStudy::Row& r, const std::string& csv)
{
  if (r.status != RunOutcome::Status::completed)
    return nan;
  if (csv == "lambda_p_l2")
    return r.lambda_p.l2;
  if (csv == "lambda_p_max")
    return r.lambda_p.max;
  if (csv == "wire_l2")
    return r.wire.l2;
  if (csv == "wire_h1")
    return r.wire.h1;
  if (csv == "f_min_carrier")
    return r.carrier_frequency_error;
  return r.contact_wire_frequency_error;
}

struct Column
{
  std::string legend; ///< what the column is
  std::string csv;    ///< column key of the table and the CSV
};

/// Which plot shows column @p csv: 0 lambda_p, 1 the wire, 2 the frequencies.
unsigned int plot_of(const std::string& csv)
{
  return csv.rfind("lambda_p", 0) == 0 ? 0 : csv.rfind("wire", 0) == 0 ? 1 : 2;
}

std::vector<Column> columns(const StudyParameters& s, const bool refines_space)
{
  std::vector<Column> c = {
      {"lambda_p_l2 [N]: (1/T int_0^T |lambda_p - lambda_p,ref|^2 dt)^(1/2)",
       "lambda_p_l2"},
      {"lambda_p_max [N]: max_t |lambda_p - lambda_p,ref|", "lambda_p_max"}};
  if (s.wire_errors)
    c.insert(c.end(),
             {{"wire_l2 [m^1.5]: L2 norm of w_w - w_w,ref at t_e", "wire_l2"},
              {"wire_h1 [m^0.5]: H1 seminorm of w_w - w_w,ref at t_e", "wire_h1"}});
  if (s.eigenfrequency_errors && refines_space)
    c.insert(c.end(),
             {{"f_min_carrier [Hz]: |f_min - f_min,ref| of the carrier", "f_min_carrier"},
              {"f_min_contact_wire [Hz]: |f_min - f_min,ref| of the contact wire",
               "f_min_contact_wire"}});
  return c;
}
} // namespace

ConvergenceStudy::ConvergenceStudy(const StudyCase& p) : parameters(p), plan_(p) {}

double ConvergenceStudy::refinement_parameter(const StudyRun& run) const
{
  return plan_.refines_space() ? parameters.catenary.length() / run.n_intervals
                               : run.time_step;
}

std::vector<double> ConvergenceStudy::refinement_parameters(const unsigned int m) const
{
  std::vector<double> s;
  for (const Row& r : rows_[m])
    s.push_back(refinement_parameter(r.run));
  return s;
}

void ConvergenceStudy::run()
{
  check_study_grids(plan_.runs(), parameters);
  const StudyParameters& s = parameters.study;
  RunRequest request;
  request.wire_samples = s.error_table && s.wire_errors ? plan_.finest_n_intervals() : 0;
  request.eigenfrequencies =
      s.error_table && s.eigenfrequency_errors && plan_.refines_space();
  if (s.contact_statistics)
    request.contact_statistics = parameters.statistics;
  const RunDistribution distribution;
  root = distribution.is_root();
  const std::vector<RunOutcome> outcomes = distribution.run_and_gather(
      plan_.runs().size(), [&](const unsigned int k)
      { return execute_study_run(plan_.runs()[k], parameters, request); });
  if (!root)
    return;
  rows_.assign(plan_.n_methods(), {});
  if (s.contact_statistics)
    collect_contact_statistics(outcomes);
  if (s.error_table)
    compare_with_references(outcomes);
}

void ConvergenceStudy::collect_contact_statistics(const std::vector<RunOutcome>& outcomes)
{
  contact_.clear();
  for (unsigned int m = 0; m < plan_.n_methods(); ++m)
  {
    std::vector<ContactConvergence::Run> runs;
    std::vector<double> s;
    for (unsigned int k = 0; k < plan_.n_refinements(); ++k)
    {
      const StudyRun& run = plan_.runs()[plan_.index(m, k)];
      const RunOutcome& o = outcomes[plan_.index(m, k)];
      runs.push_back(
          {run, run.contact_law_in(parameters), o.status, o.message, o.contact});
      s.push_back(refinement_parameter(run));
    }
    contact_.emplace_back(std::move(runs), std::move(s));
  }
}

void ConvergenceStudy::compare_with_references(const std::vector<RunOutcome>& outcomes)
{
  for (unsigned int m = 0; m < plan_.n_methods(); ++m)
  {
    const RunOutcome& ref = outcomes[plan_.reference_index(m)];
    if (ref.status != RunOutcome::Status::completed)
      throw SimulationError("reference run " +
                            plan_.runs()[plan_.reference_index(m)].label() + " " +
                            to_string(ref.status) + ": " + ref.message);
    const unsigned int n_rows =
        plan_.n_refinements() - (plan_.separate_reference() ? 0 : 1);
    for (unsigned int k = 0; k < n_rows; ++k)
    {
      const RunOutcome& o = outcomes[plan_.index(m, k)];
      Row row;
      row.run = plan_.runs()[plan_.index(m, k)];
      row.status = o.status;
      row.message = o.message;
      row.cpu_seconds = o.cpu_seconds;
      if (o.status == RunOutcome::Status::completed)
      {
        row.lambda_p = compare_series(o.t, o.lambda_p, ref.t, ref.lambda_p);
        if (!o.wire.empty())
          row.wire = compare_profiles(o.wire, ref.wire, parameters.catenary.length());
        row.carrier_frequency_error = std::abs(o.f_min_carrier - ref.f_min_carrier);
        row.contact_wire_frequency_error =
            std::abs(o.f_min_contact_wire - ref.f_min_contact_wire);
      }
      rows_[m].push_back(row);
    }
  }
}

void ConvergenceStudy::write(std::ostream& out) const
{
  if (!root)
    return;
  const StudyParameters& s = parameters.study;
  const std::string name = s.output_name.empty() ? "convergence" : s.output_name;
  if (s.error_table)
    write_errors(out, name);
  if (s.contact_statistics)
    write_contact_statistics(out, name);
}

void ConvergenceStudy::write_errors(std::ostream& out, const std::string& name) const
{
  const StudyParameters& s = parameters.study;
  const std::string dir = parameters.output.directory;
  const bool space = plan_.refines_space();
  const std::vector<Column> cols = columns(s, space);
  std::ostringstream txt, csv;
  csv << "discretisation,integrator,contact_law,n_intervals,time_step";
  for (const auto& c : cols)
    csv << ',' << c.csv << ',' << c.csv << "_order";
  csv << ",cpu_seconds,status\n";

  // One plot per quantity (units differ): lambda_p, the wire, the frequencies.
  std::vector<LogLogCurve> curves[3];
  for (unsigned int m = 0; m < plan_.n_methods(); ++m)
  {
    const auto& rows = rows_[m];
    const StudyRun& ref = plan_.runs()[plan_.reference_index(m)];
    std::ostringstream heading;
    heading << "Convergence of " << plan_.runs()[plan_.index(m, 0)].method() << " ("
            << (space ? "observed orders in h = L/(N+1)" : "observed orders in dt")
            << ") against " << (plan_.separate_reference() ? "the separate run " : "")
            << ref.label() << '\n';
    for (const auto& c : cols)
      heading << "  " << c.legend << '\n';
    heading << "  (columns ...red.rate.log2: observed order "
            << (space ? "in h" : "in dt") << " between a row and the one above)\n";
    dealii::ConvergenceTable table;
    const std::vector<double> parameter = refinement_parameters(m);
    bool any_interpolated = false;
    for (const Row& r : rows)
    {
      table.add_value("N+1", r.run.n_intervals);
      table.add_value("dt", r.run.time_step);
      if (!space)
        table.add_value("1/dt", 1. / r.run.time_step);
      for (const auto& c : cols)
        table.add_value(c.csv, value(r, c.csv));
      any_interpolated = any_interpolated || r.lambda_p.interpolated;
    }
    table.set_scientific("dt", true);
    table.set_precision("dt", 3);
    if (!space)
    {
      table.set_scientific("1/dt", true);
      table.set_precision("1/dt", 3);
    }
    for (const auto& c : cols)
    {
      table.set_scientific(c.csv, true);
      table.set_precision(c.csv, 3);
      // dim = 1: the grid has N+1 cells in one dimension (TOOLCHAIN.md).
      table.evaluate_convergence_rates(c.csv, space ? "N+1" : "1/dt",
                                       dealii::ConvergenceTable::reduction_rate_log2, 1);
    }
    for (auto* stream : {&out, static_cast<std::ostream*>(&txt)})
    {
      *stream << heading.str();
      table.write_text(*stream, dealii::TableHandler::table_with_headers);
    }
    for (const Row& r : rows)
      if (r.status != RunOutcome::Status::completed)
        for (auto* stream : {&out, static_cast<std::ostream*>(&txt)})
          *stream << "  " << to_string(r.status) << ": " << r.run.label() << ": "
                  << r.message << '\n';
    if (any_interpolated)
      for (auto* stream : {&out, static_cast<std::ostream*>(&txt)})
        *stream << "  (the reference's step does not divide every run's step: "
                   "lambda_p_ref interpolated linearly in time)\n";

    std::vector<std::vector<double>> orders;
    for (const auto& c : cols)
    {
      std::vector<double> e;
      for (const Row& r : rows)
        e.push_back(value(r, c.csv));
      orders.push_back(observed_orders(e, parameter));
      LogLogCurve curve{plan_.runs()[plan_.index(m, 0)].method() + ": " + c.csv, {}};
      for (std::size_t k = 0; k < rows.size(); ++k)
        curve.points.emplace_back(space ? rows[k].run.n_intervals : rows[k].run.time_step,
                                  e[k]);
      curves[plot_of(c.csv)].push_back(curve);
    }
    csv << std::setprecision(6);
    for (std::size_t k = 0; k < rows.size(); ++k)
    {
      const Row& r = rows[k];
      csv << to_string(r.run.discretisation) << ',' << r.run.integrator << ','
          << r.run.contact_law_in(parameters) << ',' << r.run.n_intervals << ','
          << r.run.time_step;
      for (std::size_t c = 0; c < cols.size(); ++c)
      {
        const double e = value(r, cols[c].csv);
        csv << ',';
        if (std::isfinite(e))
          csv << e;
        csv << ',';
        if (std::isfinite(orders[c][k]))
          csv << std::fixed << std::setprecision(3) << orders[c][k] << std::defaultfloat
              << std::setprecision(6);
      }
      csv << ',' << std::setprecision(4) << r.cpu_seconds << std::setprecision(6) << ','
          << to_string(r.status) << '\n';
    }
  }
  write_file_atomically(dir + "/" + name + ".txt", txt.str());
  write_file_atomically(dir + "/" + name + ".csv", csv.str());
  out << "  wrote " << name << ".txt, " << name << ".csv";
  if (parameters.output.plots)
  {
    const char* suffix[3] = {"", "_wire", "_frequencies"};
    const char* y_label[3] = {"error of lambda_p [N]",
                              "error of the contact wire at t_e: L2 [m^1.5], H1 [m^0.5]",
                              "error of the lowest eigenfrequency [Hz]"};
    for (unsigned int i = 0; i < 3; ++i)
      if (!curves[i].empty())
      {
        const std::string plot = name + suffix[i];
        const bool drawn =
            plot_log_log(dir, plot, "Convergence: errors against the reference",
                         space ? "N+1" : "dt [s]", y_label[i], curves[i]);
        out << (drawn ? ", " + plot + ".png"
                      : std::string(" (gnuplot not found: no PNG)"))
            << ", " << plot << ".gp";
      }
  }
  out << " to " << dir << '\n';
}

void ConvergenceStudy::write_contact_statistics(std::ostream& out,
                                                const std::string& name) const
{
  const std::string dir = parameters.output.directory;
  const StatisticsParameters& st = parameters.statistics;
  std::ostringstream text;
  const ContactConvergence::Run* smallest = nullptr;
  for (unsigned int m = 0; m < plan_.n_methods(); ++m)
  {
    text << "Contact statistics of " << plan_.runs()[plan_.index(m, 0)].method()
         << ": pantograph 1, "
         << st.evaluation_window(parameters.catenary.support_positions()).describe()
         << ", ";
    if (st.low_pass_cutoff > 0.)
      text << "low pass " << st.low_pass_cutoff << " Hz (order " << st.low_pass_order
           << ")";
    else
      text << "no low pass (Statistics/Low-pass cut-off = 0: no filtered figures)";
    text << "; events: those of the episodes at the resolution "
         << 1e3 * st.episode_resolution
         << " ms (Statistics/Episode resolution: shorter reclosures merged, shorter "
            "episodes counted as short episodes)"
         << "; min unilat.: the smallest force of any unilateral constraint at any "
            "time point\n";
    contact_[m].write_text(text, plan_.refines_space());
    const ContactConvergence::Run* r = contact_[m].smallest_unilateral_force();
    if (r && (!smallest ||
              r->figures.min_unilateral_force < smallest->figures.min_unilateral_force))
      smallest = r;
  }
  if (smallest)
    text << "Smallest unilateral force of all runs: "
         << smallest->figures.min_unilateral_force << " N ("
         << smallest->figures.min_unilateral_constraint
         << ", t = " << smallest->figures.min_unilateral_time << " s, "
         << smallest->run.label()
         << "): " << (smallest->figures.min_unilateral_force >= 0. ? ">= 0" : "NEGATIVE")
         << '\n';
  out << text.str();
  std::ostringstream csv;
  csv << ContactConvergence::csv_header() << '\n';
  for (const ContactConvergence& c : contact_)
    c.write_csv(csv);
  write_file_atomically(dir + "/" + name + "_contact.txt", text.str());
  write_file_atomically(dir + "/" + name + "_contact.csv", csv.str());
  out << "  wrote " << name << "_contact.txt, " << name << "_contact.csv to " << dir
      << '\n';
}

void run_convergence_study(const StudyCase& parameters, std::ostream& out)
{
  ConvergenceStudy study(parameters);
  const RunDistribution distribution;
  if (distribution.is_root())
    out << "Convergence study: " << study.plan().runs().size() << " runs on "
        << distribution.size() << (distribution.size() == 1 ? " process" : " MPI ranks")
        << '\n';
  study.run();
  study.write(out);
}
} // namespace pantocat
