#include <pantocat/base/number_format.h>
#include <pantocat/base/safe_files.h>
#include <pantocat/io/html_report.h>
#include <pantocat/io/run_report.h>
#include <pantocat/simulation/switch_episodes.h>

#include <cmath>
#include <sstream>

namespace pantocat
{
namespace
{
using Row = std::vector<HtmlReport::Cell>;

/// The text of the SVG file @p name in @p dir, empty if it is not a regular file.
std::string svg_of(const std::string& dir, const std::string& name)
{
  const FileContent c = read_regular_file(dir + "/" + name, 64u << 20, false);
  return c.bytes ? *c.bytes : std::string();
}

/// The case: print_case_summary()'s lines as a list, without their indent.
void case_section(HtmlReport& page, const RunRecord& r)
{
  std::ostringstream summary;
  print_case_summary(summary, r.runner);
  std::istringstream lines(summary.str());
  std::vector<std::string> items;
  for (std::string line; std::getline(lines, line);)
    items.push_back(line.substr(line.find_first_not_of(' ')));
  const Case& c = r.runner.case_data();
  std::ostringstream method;
  method << "space: " << to_string(c.discretisation.method)
         << ", N+1 = " << c.discretisation.n_intervals
         << "; time: " << c.time_integration.integrator
         << ", dt = " << number_to_string(c.time_integration.time_step, 6) << " s, "
         << r.result.integrator.steps
         << " steps to t = " << number_to_string(r.result.end_time, 6) << " s in "
         << number_to_string(r.result.time_loop_seconds, 3) << " s";
  items.push_back(method.str());
  page.heading("The case", 2, "case").list(items);
}

/// The window's figures, raw and after the low pass.
void statistics_table(HtmlReport& page, const ContactForceStatistics& s,
                      const std::string& id)
{
  const ForceFigures& raw = s.raw;
  const ForceFigures* low = s.filtered ? &*s.filtered : nullptr;
  std::vector<Row> rows;
  const auto add = [&](const std::string& name, double ForceFigures::*f, int digits)
  {
    Row row{{name}, HtmlReport::number(raw.*f, digits)};
    if (low != nullptr)
      row.push_back(HtmlReport::number(low->*f, digits));
    rows.push_back(row);
  };
  add("mean F_m [N]", &ForceFigures::mean, 5);
  add("standard deviation sigma [N]", &ForceFigures::std, 4);
  add("F_m + 3 sigma [N]", &ForceFigures::mean_plus_3std, 5);
  add("F_m - 3 sigma [N]", &ForceFigures::mean_minus_3std, 5);
  add("maximum [N]", &ForceFigures::max, 5);
  add("minimum [N]", &ForceFigures::min, 5);
  add("contact loss [% of the time]", &ForceFigures::contact_loss_percent, 3);
  std::vector<std::string> header{"window " + s.window.describe(), "raw"};
  if (low != nullptr)
    header.push_back("low pass " + number_to_string(s.filter_cutoff_hz, 4) + " Hz");
  page.table(header, rows, id);
  page.note(std::to_string(raw.n_points) + " time points, x_p from " +
            number_to_string(s.first_position, 6) + " to " +
            number_to_string(s.last_position, 6) + " m, t from " +
            number_to_string(s.first_time, 6) + " to " +
            number_to_string(s.last_time, 6) + " s" +
            (low != nullptr
                 ? "; low pass: Butterworth of order " + std::to_string(s.filter_order) +
                       ", forward and backward over the whole run"
                 : ""));
}

/// The assessment: one row per criterion and the verdict.
void assessment_table(HtmlReport& page, const Assessment& a, const std::string& id)
{
  std::vector<Row> rows;
  for (const CriterionResult& c : a.criteria)
    rows.push_back(
        {{c.quantity},
         {number_to_string(c.value, 4) + " " + c.unit, "number"},
         {(c.at_most ? "<= " : "> ") + number_to_string(c.limit, 4) + " " + c.unit},
         {c.rule},
         c.passed ? HtmlReport::Cell{"pass", "pass"} : HtmlReport::Cell{"FAIL", "fail"}});
  page.paragraph("Assessment of the " + a.basis + " force at " +
                 number_to_string(a.speed_kmh, 4) +
                 " km/h: " + (a.passed() ? "passed" : "FAILED") + ".");
  page.table({"criterion", "value", "limit", "rule", "result"}, rows, id);
  page.note("Criteria of subsection Assessment: the values commonly quoted from EN 50367 "
            "and the TSI Energy; check them against your copy of the standard.");
}

/// Per pantograph in contact: its window's statistics and assessment.
void pantograph_sections(HtmlReport& page, const RunRecord& r)
{
  const SimulationLayout& layout = r.runner.layout();
  for (unsigned int k = 0; k < r.contacts.size(); ++k)
    if (r.contacts[k] != nullptr)
    {
      const std::string n = std::to_string(k + 1);
      page.heading(layout.contacts().size() > 1
                       ? "Contact force of " + layout.pantographs[k].name
                       : std::string("Contact force"),
                   2, "pantograph-" + n);
      statistics_table(page, r.contacts[k]->result(), "statistics-" + n);
      if (k < r.assessments.size() && !r.assessments[k].criteria.empty())
        assessment_table(page, r.assessments[k], "assessment-" + n);
      else
        page.note("Not assessed (Assessment/Enabled = false, or no window).");
    }
}

/// On a line: each overlap's figures per pantograph and contact wire (LineWindows).
void overlap_table(HtmlReport& page, const RunRecord& r)
{
  if (r.line == nullptr || r.line->evaluations().empty())
    return;
  std::vector<Row> rows;
  for (const LineWindows::Evaluation& e : r.line->evaluations())
  {
    const ContactForceStatistics& s = e.statistics->result();
    Row row{{r.runner.layout().pantographs[e.pantograph].name},
            {e.window + " (" + number_to_string(s.window.start, 6) + "-" +
             number_to_string(s.window.end, 6) + " m)"},
            {e.wire}};
    for (const ForceFigures* f : {&s.raw, s.filtered ? &*s.filtered : nullptr})
      for (const double x :
           {f ? f->mean : NAN, f ? f->std : NAN, f ? f->max : NAN, f ? f->min : NAN})
        row.push_back(HtmlReport::number(x, 4));
    rows.push_back(row);
  }
  page.heading("The overlaps", 2, "overlaps");
  page.table({"pantograph", "window", "contact wire", "raw F_m [N]", "raw sigma [N]",
              "raw max [N]", "raw min [N]", "low-pass F_m [N]", "low-pass sigma [N]",
              "low-pass max [N]", "low-pass min [N]"},
             rows, "overlaps");
  page.note("On all wires the pantograph's contact force; on one wire its share. The low "
            "pass of a force that switches to zero overshoots below 0: a negative "
            "low-passed minimum is the filter's, not a pushing contact.");
}

/// Largest number of droppers listed one by one in the report.
constexpr std::size_t max_slack_rows = 60;

/// "[t0, t1] s at x_p = a-b m" of an episode of pantograph @p k.
std::string located(const RunRecord& r, const unsigned int k, const SwitchEpisode& e)
{
  const auto& [t0, t1] = e.span;
  return "[" + number_to_string(t0, 5) + ", " + number_to_string(t1, 5) +
         "] s at x_p = " + number_to_string(r.position_at(k, t0), 5) + "-" +
         number_to_string(r.position_at(k, t1), 5) + " m";
}

/// The droppers that went slack: intervals, time slack, the first episode with its place.
void slack_table(HtmlReport& page, const RunRecord& r, const unsigned int k)
{
  const auto slack = r.statistics.dropper_slack_intervals();
  const std::vector<double> x = r.runner.dropper_positions(); // along the line
  std::vector<Row> rows;
  std::size_t slackened = 0;
  for (std::size_t j = 0; j < slack.size(); ++j)
  {
    if (slack[j].empty())
      continue;
    if (++slackened > max_slack_rows)
      continue;
    const auto episodes = switch_episodes(slack[j], r.episode_resolution);
    double open = 0.;
    for (const Interval& i : slack[j])
      open += i.second - i.first;
    rows.push_back({{std::to_string(j + 1)},
                    HtmlReport::number(j < x.size() ? x[j] : NAN, 6),
                    {std::to_string(slack[j].size()), "number"},
                    HtmlReport::number(1e3 * open, 3),
                    {located(r, k, episodes.front())}});
  }
  if (slackened == 0)
  {
    page.paragraph("No dropper went slack.");
    return;
  }
  page.paragraph(std::to_string(slackened) + " of " + std::to_string(slack.size()) +
                 " droppers went slack in the whole run" +
                 (slackened > max_slack_rows
                      ? "; the first " + std::to_string(max_slack_rows) + " listed"
                      : "") +
                 " (positions x_p of " + r.runner.layout().pantographs[k].name + "):");
  page.table({"dropper", "x [m]", "slack intervals", "time slack [ms]", "first episode"},
             rows, "dropper-slack");
}

/// Whole-run extremes and contact-loss episodes of every pantograph in contact.
void contact_events(HtmlReport& page, const RunRecord& r)
{
  const SimulationLayout& layout = r.runner.layout();
  std::vector<Row> rows;
  for (unsigned int k = 0; k < layout.pantographs.size(); ++k)
    if (layout.pantographs[k].has_contact())
    {
      const auto& f = r.statistics.contact_force(k);
      const auto loss =
          switch_episodes(r.statistics.contact_loss_intervals(k), r.episode_resolution);
      std::string losses = loss.empty() ? "none" : std::to_string(loss.size()) + ": ";
      for (std::size_t i = 0; i < std::min<std::size_t>(loss.size(), 5); ++i)
        losses += (i ? "; " : "") + located(r, k, loss[i]);
      if (loss.size() > 5)
        losses += "; ...";
      rows.push_back({{layout.pantographs[k].name},
                      {number_to_string(f.max, 5) +
                       " N at x_p = " + number_to_string(f.max_position, 5) + " m"},
                      {number_to_string(f.min, 5) +
                       " N at x_p = " + number_to_string(f.min_position, 5) + " m"},
                      {losses}});
    }
  page.table(
      {"pantograph", "whole-run maximum", "whole-run minimum", "contact-loss episodes"},
      rows, "contact-events");
  page.note("Whole-run figures include the start and the approach to an anchor, outside "
            "the evaluation window; the assessment uses the window only.");
}

/// The entries the case file and the command line set.
void inputs_table(HtmlReport& page, const RunRecord& r)
{
  std::vector<Row> rows;
  for (const auto& [name, value] : r.inputs)
    rows.push_back({{name}, {value}});
  page.heading("Inputs", 2, "inputs");
  if (rows.empty())
    page.paragraph("Every entry has its default.");
  else
    page.table({"entry", "value"}, rows, "inputs");
}
} // namespace

void write_run_report(const std::string& dir, const RunRecord& r,
                      const std::vector<ReportFigure>& figures)
{
  const Case& c = r.runner.case_data();
  const std::string extent =
      c.line.is_line() ? std::to_string(c.line.n_sections) + " tension sections"
                       : std::to_string(c.catenary.number_of_spans()) + " spans";
  HtmlReport page("pantocat-fem report: " + extent + ", " +
                  number_to_string(3.6 * c.scene.pantographs[0].parameters.speed, 4) +
                  " km/h");
  case_section(page, r);
  pantograph_sections(page, r);
  overlap_table(page, r);
  page.heading("Along the line", 2, "figures");
  if (figures.empty())
    page.note("No figures: Output/Plots is false or gnuplot is not installed.");
  for (const ReportFigure& f : figures)
    if (const std::string svg = svg_of(dir, f.svg); !svg.empty())
      page.figure(svg, f.caption);
  page.heading("Events", 2, "events");
  contact_events(page, r);
  const auto& pantographs = r.runner.layout().pantographs;
  unsigned int first = 0; // the positions of the first pantograph in contact
  while (first + 1 < pantographs.size() && !pantographs[first].has_contact())
    ++first;
  slack_table(page, r, first);
  inputs_table(page, r);
  page.note(std::string("pantocat-fem ") + PANTOCAT_VERSION +
            "; the figures of this page are in summary.json, the series in "
            "contact_force.csv and time_series.csv.");
  write_file_atomically(dir + "/report.html", page.str());
}
} // namespace pantocat
