#include <pantocat/base/input_error.h>
#include <pantocat/io/log_log_plot.h>
#include <pantocat/studies/convergence_study.h>
#include <pantocat/studies/run_distribution.h>

#include <deal.II/base/convergence_table.h>

#include <cmath>
#include <fstream>
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

std::vector<double> ConvergenceStudy::refinement_parameters(const unsigned int m) const
{
  std::vector<double> s;
  for (const Row& r : rows_[m])
    s.push_back(plan_.refines_space() ? parameters.catenary.length() / r.run.n_intervals
                                      : r.run.time_step);
  return s;
}

void ConvergenceStudy::run()
{
  check_study_grids(plan_.runs(), parameters);
  RunRequest request;
  request.wire_samples = parameters.study.wire_errors ? plan_.finest_n_intervals() : 0;
  request.eigenfrequencies =
      parameters.study.eigenfrequency_errors && plan_.refines_space();
  const RunDistribution distribution;
  root = distribution.is_root();
  const std::vector<RunOutcome> outcomes = distribution.run_and_gather(
      plan_.runs().size(), [&](const unsigned int k)
      { return execute_study_run(plan_.runs()[k], parameters, request); });
  if (!root)
    return;

  rows_.assign(plan_.n_methods(), {});
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
  const std::string dir = parameters.output.directory;
  const bool space = plan_.refines_space();
  const std::vector<Column> cols = columns(s, space);
  std::ofstream txt(dir + "/" + name + ".txt");
  std::ofstream csv(dir + "/" + name + ".csv");
  csv << "discretisation,integrator,n_intervals,time_step";
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
          << r.run.n_intervals << ',' << r.run.time_step;
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
  if (!txt || !csv)
    throw SimulationError("cannot write " + dir + "/" + name + ".txt or .csv");
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
