#include <pantocat/base/safe_files.h>
#include <pantocat/io/csv_number.h>
#include <pantocat/io/statistics_report.h>

#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>

#include <algorithm>
#include <fstream>
#include <iomanip>
#include <optional>
#include <sstream>

namespace pantocat
{
namespace
{
/// Opens the object @p key (raw or filtered) with one set of figures; the caller closes
/// it.
JsonWriter& write_figures(JsonWriter& json, const std::string& key, const ForceFigures& f)
{
  return json.begin_object(key)
      .value("mean", f.mean)
      .value("std", f.std)
      .value("max", f.max)
      .value("min", f.min)
      .value("mean_plus_3std", f.mean_plus_3std)
      .value("mean_minus_3std", f.mean_minus_3std)
      .value("contact_loss_percent", f.contact_loss_percent);
}

void write_window(JsonWriter& json, const ContactForceStatistics& s)
{
  const EvaluationWindow& w = s.window;
  json.begin_object("window").begin_array("x");
  json.value("", w.whole_run() ? s.first_position : w.start)
      .value("", w.whole_run() ? s.last_position : w.end)
      .end_array();
  if (w.given_by_spans())
    json.begin_array("spans")
        .value("", static_cast<unsigned long>(w.first_span))
        .value("", static_cast<unsigned long>(w.last_span))
        .end_array();
  else
    json.null("spans");
  json.value("n_points", s.raw.n_points).end_object();
}

void write_steady_arms(JsonWriter& json, const ContactForceStatistics& s)
{
  if (const auto largest = s.max_steady_arm_uplift())
    json.value("max_steady_arm_uplift_m", *largest);
  else
    json.null("max_steady_arm_uplift_m");
  json.begin_array("steady_arms");
  for (const SteadyArmUplift& arm : s.steady_arms)
    json.begin_object()
        .value("x", arm.x)
        .value("max_uplift_m", arm.max_uplift)
        .end_object();
  json.end_array();
}
} // namespace

void write_slack_events(JsonWriter& json, const std::string& key,
                        const DropperSlackEvents& events)
{
  json.begin_object(key).value("total", events.total).begin_array("per_dropper");
  for (const unsigned long n : events.per_dropper)
    json.value("", n);
  json.end_array().end_object();
}

void write_statistics(JsonWriter& json, const ContactForceStatistics& s,
                      const DropperSlackEvents& slack_in_window)
{
  json.begin_object("statistics");
  write_window(json, s);
  write_figures(json, "raw", s.raw).end_object();
  if (s.filtered)
    write_figures(json, "filtered", *s.filtered)
        .value("cutoff_hz", s.filter_cutoff_hz)
        .value("order", static_cast<unsigned long>(s.filter_order))
        .end_object();
  else
    json.null("filtered");
  write_steady_arms(json, s);
  json.begin_array("max_uplift_at_droppers");
  for (const double uplift : s.max_uplift_at_droppers)
    json.value("", uplift);
  json.end_array();
  write_slack_events(json, "dropper_slack_events_in_window", slack_in_window);
  json.end_object();
}

void write_line_windows(JsonWriter& json, const LineWindows& line,
                        const SimulationLayout& layout)
{
  json.begin_array("line_windows");
  for (const LineWindows::Evaluation& e : line.evaluations())
  {
    json.begin_object()
        .value("pantograph", layout.pantographs[e.pantograph].name)
        .value("window", e.window)
        .value("wire", e.wire);
    write_statistics(json, e.statistics->result(), {});
    json.end_object();
  }
  json.end_array();
}

namespace
{
/// "F_m 163.0, sigma 47.6, F_max 340.1, F_min 21.3" of @p f [N].
std::string figures_text(const ForceFigures& f)
{
  std::ostringstream s;
  s << std::fixed << std::setprecision(1) << "F_m " << f.mean << ", sigma " << f.std
    << ", F_max " << f.max << ", F_min " << f.min;
  return s.str();
}
} // namespace

void print_line_windows(std::ostream& out, const LineWindows& line,
                        const SimulationLayout& layout, const bool detailed)
{
  if (line.evaluations().empty())
    return;
  out << "  the line's overlaps" << (detailed ? " and contact wires" : "")
      << " [N] (raw | low-passed; per contact wire in summary.json):\n";
  for (const LineWindows::Evaluation& e : line.evaluations())
  {
    if (!detailed && e.wire != "all wires")
      continue;
    const ContactForceStatistics& s = e.statistics->result();
    out << "    " << layout.pantographs[e.pantograph].name << ", " << e.window << " ("
        << std::setprecision(6) << s.window.start << "-" << s.window.end << " m)"
        << (e.wire == "all wires" ? "" : ", " + e.wire) << ": " << figures_text(s.raw);
    if (s.filtered)
      out << " | " << figures_text(*s.filtered);
    out << '\n';
  }
}

std::vector<std::string>
contact_force_column_names(const std::vector<ContactForceColumns>& pantographs)
{
  std::vector<std::string> names{"t"};
  for (const ContactForceColumns& p : pantographs)
    for (const std::string name : {"x_p", "lambda_p", "lambda_p_filtered"})
      names.push_back(name + p.suffix);
  return names;
}

void write_contact_force(const std::string& file,
                         const std::vector<ContactForceColumns>& pantographs)
{
  // The numbers as a stream with precision 10 writes them (append_csv_number()).
  std::string csv;
  const std::vector<std::string> names = contact_force_column_names(pantographs);
  for (std::size_t c = 0; c < names.size(); ++c)
    csv.append(c ? "," : "").append(names[c]);
  csv += '\n';
  const std::size_t n_points =
      pantographs.empty() ? 0 : pantographs.front().statistics->series().t.size();
  csv.reserve(csv.size() + n_points * (18 + 54 * pantographs.size()));
  for (std::size_t n = 0; n < n_points; ++n)
  {
    append_csv_number(csv, pantographs.front().statistics->series().t[n]);
    for (const ContactForceColumns& p : pantographs)
      for (const double x :
           {p.statistics->series().x_p[n], p.statistics->series().lambda_p[n],
            p.statistics->filtered_force()[n]})
      {
        csv += ',';
        append_csv_number(csv, x);
      }
    csv += '\n';
  }
  write_file_atomically(file, csv);
}

namespace
{
/// Up to this many droppers with events, a description names each.
constexpr std::size_t max_droppers_named = 5;
} // namespace

std::string describe_slack_events(const DropperSlackEvents& events)
{
  if (events.total == 0)
    return "none";
  std::ostringstream s;
  std::size_t droppers = 0, most = 0;
  for (std::size_t j = 0; j < events.per_dropper.size(); ++j)
  {
    droppers += events.per_dropper[j] > 0;
    if (events.per_dropper[j] > events.per_dropper[most])
      most = j;
  }
  if (droppers > max_droppers_named)
  {
    s << "total " << events.total << " on " << droppers << " droppers (most: dropper "
      << most + 1 << ": " << events.per_dropper[most] << ')';
    return s.str();
  }
  s << "total " << events.total << " (";
  bool first = true;
  for (std::size_t j = 0; j < events.per_dropper.size(); ++j)
    if (events.per_dropper[j] > 0)
    {
      s << (first ? "" : ", ") << "dropper " << j + 1 << ": " << events.per_dropper[j];
      first = false;
    }
  s << ')';
  return s.str();
}

namespace
{
/// Up to this many droppers, the screen lists the uplift of each.
constexpr std::size_t max_droppers_listed = 10;

/// One row of the side-by-side table: a label, the raw and the filtered figure.
void print_row(std::ostream& out, const std::string& label, const double raw,
               const std::optional<double>& filtered)
{
  out << "    " << std::left << std::setw(18) << label << std::right << std::setw(10)
      << raw;
  if (filtered)
    out << std::setw(20) << *filtered;
  out << '\n';
}

void print_figures(std::ostream& out, const ContactForceStatistics& s)
{
  out << "    " << std::setw(18) << "" << std::setw(10) << "raw";
  if (s.filtered)
    out << std::setw(20)
        << ("low pass " + number_to_string(s.filter_cutoff_hz, 4) + " Hz");
  out << '\n' << std::fixed << std::setprecision(2);
  using Field = double ForceFigures::*;
  const std::pair<const char*, Field> rows[] = {
      {"mean [N]", &ForceFigures::mean},
      {"std [N]", &ForceFigures::std},
      {"max [N]", &ForceFigures::max},
      {"min [N]", &ForceFigures::min},
      {"mean + 3 std [N]", &ForceFigures::mean_plus_3std},
      {"mean - 3 std [N]", &ForceFigures::mean_minus_3std},
      {"contact loss [%]", &ForceFigures::contact_loss_percent}};
  for (const auto& [label, field] : rows)
    print_row(out, label, s.raw.*field,
              s.filtered ? std::optional<double>((*s.filtered).*field) : std::nullopt);
}

void print_uplift(std::ostream& out, const ContactForceStatistics& s)
{
  out << std::fixed << std::setprecision(2);
  if (const auto largest = s.max_steady_arm_uplift())
  {
    out << "    max uplift at the steady arms in the window: " << 1000. * *largest
        << " mm (";
    for (std::size_t k = 0; k < s.steady_arms.size(); ++k)
      out << (k ? ", " : "") << "x = " << std::setprecision(6) << std::defaultfloat
          << s.steady_arms[k].x << " m: " << std::fixed << std::setprecision(2)
          << 1000. * s.steady_arms[k].max_uplift << " mm";
    out << ")\n";
  }
  const std::vector<double>& droppers = s.max_uplift_at_droppers;
  if (droppers.empty()) // no droppers on an elastic wire
    return;
  out << "    max uplift of the contact wire at the droppers:";
  if (droppers.size() <= max_droppers_listed)
    for (std::size_t j = 0; j < droppers.size(); ++j)
      out << (j ? "," : "") << " " << 1000. * droppers[j] << " mm";
  else // a section: the largest (every dropper's in summary.json)
  {
    const auto largest = std::max_element(droppers.begin(), droppers.end());
    out << " largest " << 1000. * *largest << " mm at dropper "
        << largest - droppers.begin() + 1 << " of " << droppers.size();
  }
  out << '\n';
}
} // namespace

void print_statistics(std::ostream& out, const ContactForceStatistics& s,
                      const DropperSlackEvents& slack_in_window)
{
  const auto flags = out.flags();
  const auto precision = out.precision();
  out << "  contact-force statistics, " << s.window.describe() << ": ";
  if (s.raw.n_points == 0)
    out << "no time point in the window\n";
  else
  {
    out << s.raw.n_points << " time points";
    if (s.filtered)
      out << "; low pass: Butterworth order " << s.filter_order
          << ", forward and backward";
    out << '\n';
    print_figures(out, s);
  }
  print_uplift(out, s);
  if (!slack_in_window.per_dropper.empty())
    out << "    dropper slack events with the pantograph in the window: "
        << describe_slack_events(slack_in_window) << '\n';
  out.flags(flags);
  out.precision(precision);
}
void write_assessment(JsonWriter& json, const Assessment& a)
{
  if (a.criteria.empty())
  {
    json.null("assessment");
    return;
  }
  json.begin_object("assessment")
      .value("speed_kmh", a.speed_kmh)
      .value("basis", a.basis)
      .value("passed", a.passed());
  json.begin_array("criteria");
  for (const CriterionResult& c : a.criteria)
    json.begin_object()
        .value("name", c.name)
        .value("value", c.value)
        .value("limit", c.limit)
        .value("relation", c.at_most ? "<=" : ">")
        .value("unit", c.unit)
        .value("rule", c.rule)
        .value("passed", c.passed)
        .end_object();
  json.end_array();
  json.end_object();
}

void print_assessment(std::ostream& out, const Assessment& a)
{
  if (a.criteria.empty())
    return;
  const auto flags = out.flags();
  const auto precision = out.precision();
  out << "  assessment (" << a.basis
      << " force; criteria of subsection Assessment, EN 50367 / TSI as commonly "
         "quoted): "
      << (a.passed() ? "passed" : "FAILED") << '\n';
  for (const CriterionResult& c : a.criteria)
  {
    std::ostringstream value, limit;
    value << std::setprecision(4) << c.value << ' ' << c.unit;
    limit << (c.at_most ? "<= " : "> ") << std::setprecision(4) << c.limit << ' '
          << c.unit;
    out << "    " << std::left << std::setw(28) << c.quantity << std::right
        << std::setw(12) << value.str() << "  " << std::left << std::setw(14)
        << limit.str() << std::right << (c.passed ? "  pass" : "  FAIL") << "  ("
        << c.rule << ")\n";
  }
  out.flags(flags);
  out.precision(precision);
}

namespace
{
/// One row of print_statistics_side_by_side(): @p label, then a cell per column.
void side_by_side_row(std::ostream& out, const std::string& label,
                      const std::vector<std::string>& cells)
{
  out << "    " << std::left << std::setw(28) << label << std::right;
  for (const std::string& cell : cells)
    out << std::setw(16) << cell;
  out << '\n';
}

/// " FAILED: sigma 52 N <= 48.5 N, ..." or " passed" (or " not assessed").
std::string verdict_line(const Assessment* a)
{
  if (a == nullptr || a->criteria.empty())
    return " not assessed";
  if (a->passed())
    return " passed";
  std::ostringstream failed;
  failed << std::setprecision(4) << " FAILED:";
  const char* separator = " ";
  for (const CriterionResult& c : a->criteria)
    if (!c.passed)
      failed << separator << c.quantity << ' ' << c.value << ' ' << c.unit
             << (c.at_most ? " > " : " <= ") << c.limit << ' ' << c.unit,
          separator = ", ";
  return failed.str();
}
} // namespace

void print_statistics_side_by_side(std::ostream& out,
                                   const std::vector<PantographFigures>& columns)
{
  const auto flags = out.flags();
  const auto precision = out.precision();
  const ContactForceStatistics& first = *columns.front().statistics;
  out << "  contact-force statistics per pantograph"
      << (first.filtered ? " (" + number_to_string(first.filter_cutoff_hz, 4) +
                               " Hz low pass; contact loss of the raw force)"
                         : "")
      << ":\n";
  std::vector<std::string> cells;
  const auto row = [&](const std::string& label, const auto& cell)
  {
    cells.clear();
    for (const PantographFigures& c : columns)
      cells.push_back(cell(c));
    side_by_side_row(out, label, cells);
  };
  const auto figure = [](const double value)
  {
    std::ostringstream text;
    text << std::fixed << std::setprecision(2) << value;
    return text.str();
  };
  const auto force = [&](double ForceFigures::*member)
  {
    return [&, member](const PantographFigures& c)
    {
      const ContactForceStatistics& s = *c.statistics;
      return figure((s.filtered ? *s.filtered : s.raw).*member);
    };
  };
  row("", [](const PantographFigures& c) { return c.name; });
  row("window x_p [m]",
      [](const PantographFigures& c)
      {
        return "[" + number_to_string(c.statistics->window.start, 6) + ", " +
               number_to_string(c.statistics->window.end, 6) + "]";
      });
  row("mean F_m [N]", force(&ForceFigures::mean));
  row("std sigma [N]", force(&ForceFigures::std));
  row("max [N]", force(&ForceFigures::max));
  row("min [N]", force(&ForceFigures::min));
  row("F_m - 3 sigma [N]", force(&ForceFigures::mean_minus_3std));
  row("contact loss, raw [%]", [&](const PantographFigures& c)
      { return figure(c.statistics->raw.contact_loss_percent); });
  row("steady-arm uplift [mm]",
      [&](const PantographFigures& c)
      {
        const auto u = c.statistics->max_steady_arm_uplift();
        return u ? figure(1e3 * *u) : std::string("-");
      });
  row("dropper slack events",
      [](const PantographFigures& c) { return std::to_string(c.slack_in_window.total); });
  if (std::any_of(columns.begin(), columns.end(),
                  [](const PantographFigures& c)
                  { return c.assessment != nullptr && !c.assessment->criteria.empty(); }))
  {
    out << "  assessment (criteria of subsection Assessment, EN 50367 / TSI as commonly "
           "quoted):\n";
    for (const PantographFigures& c : columns)
      out << "    " << c.name << ":" << verdict_line(c.assessment) << '\n';
  }
  out.flags(flags);
  out.precision(precision);
}
} // namespace pantocat
