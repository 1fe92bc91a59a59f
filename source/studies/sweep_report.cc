#include <pantocat/base/number_format.h>
#include <pantocat/base/safe_files.h>
#include <pantocat/io/html_report.h>
#include <pantocat/studies/sweep_report.h>
#include <pantocat/studies/sweep_study.h>

#include <cmath>

namespace pantocat
{
namespace
{
/// The figures of @p row whose columns begin with @p prefix ("" or "filtered_").
ForceFigures figures_of(const SweepTable::Row& row, const std::string& prefix)
{
  const auto v = [&](const std::string& name)
  { return row.values[SweepTable::statistic(prefix + name)]; };
  ForceFigures f;
  f.mean = v("mean"), f.std = v("std"), f.max = v("max"), f.min = v("min");
  f.mean_plus_3std = v("mean_plus_3std"), f.mean_minus_3std = v("mean_minus_3std");
  f.contact_loss_percent = v("contact_loss_percent");
  f.n_points = std::isfinite(f.mean) ? 1 : 0;
  return f;
}

} // namespace

Assessment assess_sweep_row(const SweepTable::Row& row, const double speed,
                            const AssessmentCriteria& criteria, const double cutoff)
{
  ContactForceStatistics s;
  s.raw = figures_of(row, "");
  if (std::isfinite(row.values[SweepTable::statistic("filtered_mean")]))
  {
    s.filtered = figures_of(row, "filtered_");
    s.filter_cutoff_hz = cutoff;
  }
  const double uplift = row.values[SweepTable::statistic("max_support_uplift_m")];
  if (std::isfinite(uplift))
    s.steady_arms.push_back({0., uplift});
  return assess(s, speed, criteria);
}

namespace
{
/// "pass", or "FAIL: sigma, maximum force" (the criteria it fails).
HtmlReport::Cell verdict(const Assessment& a)
{
  if (a.criteria.empty())
    return {"-"};
  if (a.passed())
    return {"pass", "pass"};
  std::string failed = "FAIL:";
  for (const CriterionResult& c : a.criteria)
    if (!c.passed)
      failed += (failed.size() > 5 ? ", " : " ") + c.quantity;
  return {failed, "fail"};
}

/// The speed [m/s] of @p row: its key in a speed sweep, else the base case's.
double speed_of(const SweepTable::Row& row, const SweepReportInput& input)
{
  return input.kind == SweepKind::speed ? std::stod(row.key[0]) / 3.6 : input.speed;
}

/// One pantograph's runs: key, status, the figures the assessment reads, the verdict.
void runs_table(HtmlReport& page, const SweepTable& t, const unsigned int p,
                const SweepReportInput& input)
{
  const bool low = input.filter_cutoff_hz > 0.;
  const std::string f = low ? "filtered_" : "";
  std::vector<std::string> header = t.key_columns;
  for (const std::string h :
       {"status", "F_m [N]", "sigma [N]", "max [N]", "min [N]", "F_m - 3 sigma [N]",
        "contact loss, raw [%]", "steady-arm uplift [mm]", "assessment"})
    header.push_back(h);
  std::vector<std::vector<HtmlReport::Cell>> rows;
  for (const SweepTable::Row& r : t.rows)
  {
    if (r.pantograph != p)
      continue;
    std::vector<HtmlReport::Cell> row;
    for (const std::string& k : r.key)
      row.push_back({k});
    row.push_back({r.status == "completed" ? r.status : r.status + ": " + r.reason});
    const auto v = [&](const std::string& s)
    { return r.values[SweepTable::statistic(s)]; };
    for (const std::string s : {"mean", "std", "max", "min", "mean_minus_3std"})
      row.push_back(HtmlReport::number(v(f + s), 5));
    row.push_back(HtmlReport::number(v("contact_loss_percent"), 3));
    row.push_back(HtmlReport::number(1e3 * v("max_support_uplift_m"), 4));
    const bool assessed =
        input.criteria != nullptr && input.criteria->enabled && r.status == "completed";
    row.push_back(assessed
                      ? verdict(assess_sweep_row(r, speed_of(r, input), *input.criteria,
                                                 input.filter_cutoff_hz))
                      : HtmlReport::Cell{"-"});
    rows.push_back(row);
  }
  page.table(header, rows, "runs-" + std::to_string(p));
}
} // namespace

void write_sweep_report(const std::string& dir, const SweepTable& t,
                        const SweepReportInput& input)
{
  const char* kinds[] = {"speed sweep", "parameter sweep", "Monte Carlo study"};
  HtmlReport page("pantocat-fem report: " +
                  std::string(kinds[static_cast<int>(input.kind)]) + " " + input.name);
  const bool low = input.filter_cutoff_hz > 0.;
  page.paragraph(std::to_string(t.rows.size()) + " rows in " + input.name +
                 ".csv; the figures of each pantograph's evaluation window" +
                 (low ? " after the " + number_to_string(input.filter_cutoff_hz, 4) +
                            " Hz low pass (contact loss: raw force)"
                      : " (raw force)") +
                 ".");
  for (const std::string& svg : input.svg_files)
  {
    const FileContent c = read_regular_file(dir + "/" + svg, 64u << 20, false);
    if (c.bytes)
      page.figure(*c.bytes,
                  svg.substr(0, svg.size() - 4) +
                      ": the window's figures against the swept value, with the "
                      "limits of subsection Assessment where they apply.");
  }
  for (const unsigned int p : t.pantographs())
  {
    page.heading("Pantograph " + std::to_string(p), 2, "pantograph-" + std::to_string(p));
    runs_table(page, t, p, input);
  }
  if (input.criteria != nullptr && input.criteria->enabled)
    page.note(
        "Assessment: the criteria of subsection Assessment, the values commonly "
        "quoted from EN 50367 and the TSI Energy; check them against your copy of the "
        "standard. Each run's criteria and values are those of a single run's "
        "summary.json.");
  page.note(std::string("pantocat-fem ") + PANTOCAT_VERSION);
  write_file_atomically(dir + "/" + input.name + "_report.html", page.str());
}
} // namespace pantocat
