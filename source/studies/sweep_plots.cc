#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>
#include <pantocat/base/safe_files.h>
#include <pantocat/io/plots.h>
#include <pantocat/studies/sweep_plots.h>
#include <pantocat/studies/sweep_study.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <set>
#include <sstream>

namespace pantocat
{
namespace
{
double to_value(const std::string& text)
{
  if (text.empty())
    return std::numeric_limits<double>::quiet_NaN();
  try
  {
    return std::stod(text);
  }
  catch (const std::exception&)
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
}

/// The fields of a CSV line whose last field (the reason) is quoted.
std::vector<std::string> split_row(const std::string& line, const std::size_t n_plain)
{
  std::vector<std::string> fields;
  std::size_t begin = 0;
  while (fields.size() < n_plain)
  {
    const std::size_t end = std::min(line.find(',', begin), line.size());
    fields.push_back(line.substr(begin, end - begin));
    begin = std::min(end + 1, line.size());
  }
  std::string reason = line.substr(begin);
  if (reason.size() >= 2 && reason.front() == '"')
    reason = reason.substr(1, reason.size() - 2);
  std::string unquoted;
  for (std::size_t i = 0; i < reason.size(); ++i)
    if (!(reason[i] == '"' && i + 1 < reason.size() && reason[i + 1] == '"'))
      unquoted += reason[i];
  fields.push_back(unquoted);
  return fields;
}

/// The values of statistic @p c of pantograph @p p over the completed rows, sorted.
std::vector<double> sorted_values(const SweepTable& t, const unsigned int p,
                                  const unsigned int c)
{
  std::vector<double> v;
  for (const SweepTable::Row& r : t.rows)
    if (r.pantograph == p && r.status == "completed" && std::isfinite(r.values[c]))
      v.push_back(r.values[c]);
  std::sort(v.begin(), v.end());
  return v;
}

struct Summary
{
  std::size_t n = 0;
  double mean = 0., std = 0., min = 0., p5 = 0., p50 = 0., p95 = 0., max = 0.;
};

Summary summarise(const std::vector<double>& sorted)
{
  Summary s;
  s.n = sorted.size();
  if (s.n == 0)
    return s;
  for (const double x : sorted)
    s.mean += x / s.n;
  for (const double x : sorted)
    s.std += (x - s.mean) * (x - s.mean) / s.n;
  s.std = std::sqrt(s.std);
  s.min = sorted.front(), s.max = sorted.back();
  s.p5 = percentile(sorted, 5.), s.p50 = percentile(sorted, 50.),
  s.p95 = percentile(sorted, 95.);
  return s;
}

/// 1-based CSV column of statistic @p name with @p n_keys key columns.
unsigned int csv_column(const std::string& name, const unsigned int n_keys)
{
  return n_keys + 2 + SweepTable::statistic(name);
}

/// True if some completed row of pantograph @p p has filtered figures.
bool has_filtered(const SweepTable& t, const unsigned int p)
{
  return !sorted_values(t, p, SweepTable::statistic("filtered_std")).empty();
}

/// "<name>.png" or, with several pantographs, "<name>_pantograph_<p>.png".
std::string png_name(const std::string& name, const unsigned int p, const bool several)
{
  return several ? name + "_pantograph_" + std::to_string(p) + ".png" : name + ".png";
}

/// The terminal for @p file (SVG for a .svg file, else PNG) and its output.
std::string terminal_for(const std::string& file, const unsigned int width,
                         const unsigned int height)
{
  const bool svg = file.size() > 4 && file.compare(file.size() - 4, 4, ".svg") == 0;
  return std::string("set terminal ") + (svg ? "svg" : "pngcairo") + " size " +
         std::to_string(width) + "," + std::to_string(height) + " noenhanced" +
         (svg ? " font 'sans,12' background rgb 'white'" : "") + "\n" +
         gnuplot_output(file) + "\n";
}

/// gnuplot: column @p c of the rows of pantograph @p p (NaN for the others).
std::string of_pantograph(const unsigned int p, const unsigned int c,
                          const unsigned int pantograph_column)
{
  return "(column(" + std::to_string(pantograph_column) + ") == " + std::to_string(p) +
         " ? column(" + std::to_string(c) + ") : NaN)";
}

/// The force limits of @p criteria against speed x [km/h], as plot items (none if null).
std::string force_limit_curves(const AssessmentCriteria* criteria)
{
  if (criteria == nullptr)
    return "";
  std::ostringstream items;
  items << std::setprecision(10) << criteria->mean_force_a << " * x**2 + "
        << criteria->mean_force_b << " with lines dt 2 lw 1.5 lc rgb '#008000' title "
        << gnuplot_string("target F_m " + number_to_string(criteria->mean_force_a) +
                          " v^2 + " + number_to_string(criteria->mean_force_b) + " N")
        << ", \\\n  ";
  if (criteria->max_contact_force > 0.)
    items << criteria->max_contact_force
          << " with lines dt 2 lw 1.5 lc rgb '#c00000' title "
          << gnuplot_string("limit F_max " +
                            number_to_string(criteria->max_contact_force) + " N")
          << ", \\\n  ";
  return items.str();
}

/// The speed sweep's plot of pantograph @p p.
void speed_script(std::ostream& gp, const std::string& csv, const std::string& png,
                  const SweepTable& t, const unsigned int p, const double wave_speed,
                  const AssessmentCriteria* criteria)
{
  const bool filtered = has_filtered(t, p);
  const std::string f = filtered ? "filtered_" : "";
  const auto col = [&](const std::string& s)
  { return of_pantograph(p, csv_column(s, 1), 2); };
  // Rows go speed by speed, one per pantograph: every n-th row is this one's
  // (NaN rows in between would break its lines and its band).
  const std::vector<unsigned int> all = t.pantographs();
  const std::string rows =
      "' skip 1 every " + std::to_string(all.size()) +
      "::" + std::to_string(std::find(all.begin(), all.end(), p) - all.begin()) +
      " using 1:";
  const std::string data = "'" + checked_file_name(csv) + rows;
  gp << terminal_for(png, 1000, 800) << "reset\nset datafile separator ','\n"
     << "set datafile missing ''\n"
     << "set multiplot layout 2,1\nset grid\nset key outside right\n"
     << "set lmargin at screen 0.08\nset rmargin at screen 0.62\n"
     << "set xlabel 'speed [km/h]'\nset ylabel 'contact force [N]'\n"
     << "set y2label 'contact loss [%]'\nset y2tics\nset ytics nomirror\n"
     << "set title "
     << gnuplot_string("pantograph " + std::to_string(p) +
                       ": contact force in the window" + (filtered ? " (low pass)" : "") +
                       " against speed")
     << "\nplot " << data << col(f + "mean_minus_3std") << ":"
     << col(f + "mean_plus_3std")
     << " with filledcurves lc rgb '#c8d8f0' title 'mean +/- 3 sigma', \\\n  " << data
     << col(f + "mean") << " with linespoints lc rgb '#0060c0' pt 7 title 'mean', \\\n  "
     << data << col(f + "max")
     << " with linespoints lc rgb '#c00000' pt 9 title 'max', \\\n  "
     << force_limit_curves(criteria) << data << col(f + "min")
     << " with linespoints lc rgb '#008000' pt 11 title 'min', \\\n  " << data
     << col("contact_loss_percent")
     << " axes x1y2 with linespoints dt 2 lc rgb 'black' pt 6 title 'contact loss (raw) "
        "[%]'";
  if (filtered)
    gp << ", \\\n  " << data << col("filtered_contact_loss_percent")
       << " axes x1y2 with linespoints dt 3 lc rgb '#606060' pt 4 title 'contact loss "
          "(low pass) [%]'";
  gp << "\nunset y2label\nunset y2tics\nset ytics mirror\n"
     << "set ylabel 'standard deviation sigma [N]'\nset title 'sigma against speed'\n";
  if (wave_speed > 0.)
    gp << "set arrow from " << 0.7 * wave_speed * 3.6 << ", graph 0 to "
       << 0.7 * wave_speed * 3.6 << ", graph 1 nohead dt 2 lc rgb '#c00000'\n"
       << "set label '0.7 c' at " << 0.7 * wave_speed * 3.6
       << ", graph 0.92 right offset -0.5,0 tc rgb '#c00000'\n";
  gp << "plot " << data << col("std") << " with linespoints pt 7 title 'sigma (raw)'";
  if (filtered)
    gp << ", \\\n  " << data << col("filtered_std")
       << " with linespoints pt 9 title 'sigma (low pass)'";
  if (criteria != nullptr)
    gp << ", \\\n  " << data << "(" << criteria->max_sigma_ratio << " * "
       << col(f + "mean") << ") with lines dt 2 lw 1.5 lc rgb '#c00000' title "
       << gnuplot_string("limit " + number_to_string(criteria->max_sigma_ratio) + " F_m");
  gp << "\nunset multiplot\n";
}

/// The distinct values of key column @p c, in the order they first appear.
std::vector<std::string> distinct(const SweepTable& t, const unsigned int c)
{
  std::vector<std::string> values;
  for (const SweepTable::Row& r : t.rows)
    if (std::find(values.begin(), values.end(), r.key[c]) == values.end())
      values.push_back(r.key[c]);
  return values;
}

/// The points (first entry, statistic @p c) of pantograph @p p's completed rows
/// whose second entry is @p second (any if empty), sorted by the first entry.
std::vector<std::pair<double, double>> curve_points(const SweepTable& t,
                                                    const unsigned int p,
                                                    const unsigned int c,
                                                    const std::string& second)
{
  std::vector<std::pair<double, double>> points;
  for (const SweepTable::Row& r : t.rows)
    if (r.pantograph == p && r.status == "completed" && std::isfinite(r.values[c]) &&
        (second.empty() || r.key[1] == second))
      points.emplace_back(to_value(r.key[0]), r.values[c]);
  std::sort(points.begin(), points.end());
  return points;
}

/// The axis label of statistic @p s of a sweep's table, with its unit.
std::string statistic_label(const std::string& s)
{
  if (s == "contact_loss_percent")
    return "contact loss [%]";
  if (s == "max_support_uplift_m")
    return "max steady-arm uplift [m]";
  return "contact force: " + s + " [N]";
}

/**
 * The parameter sweep's plot of statistic @p s for pantograph @p p: one curve
 * per value of the second entry (raw, and filtered if there is a low pass),
 * each an inline data block sorted by the first entry (failed runs left out),
 * so that the curves are unbroken and the script redraws without the CSV.
 */
void parameter_script(std::ostream& gp, const std::string& png, const SweepTable& t,
                      const unsigned int p, const std::string& s, const std::string& unit)
{
  const bool filtered = has_filtered(t, p);
  const std::vector<std::string> variants =
      s == "max_support_uplift_m" || !filtered
          ? std::vector<std::string>{s}
          : std::vector<std::string>{s, "filtered_" + s};
  const std::vector<std::string> seconds =
      t.key_columns.size() > 1 ? distinct(t, 1) : std::vector<std::string>{""};
  std::vector<std::string> curves;
  gp << std::setprecision(10);
  for (const std::string& v : variants)
    for (const std::string& second : seconds)
    {
      const std::string block = "$curve" + std::to_string(curves.size());
      gp << block << " << EOD\n";
      for (const auto& [x, y] : curve_points(t, p, SweepTable::statistic(v), second))
        gp << x << ',' << y << '\n';
      gp << "EOD\n";
      const std::string what = v.rfind("filtered_", 0) == 0 ? "low pass" : "raw";
      curves.push_back(block + " using 1:2 with linespoints title " +
                       gnuplot_string(second.empty() ? what
                                                     : what + ", " + t.key_columns[1] +
                                                           " = " + second));
    }
  gp << terminal_for(png, 900, 600) << "set grid\nset key below\nset xlabel "
     << gnuplot_string(t.key_columns[0] + (unit.empty() ? "" : " [" + unit + "]"))
     << "\nset ylabel " << gnuplot_string(statistic_label(s)) << "\nset title "
     << gnuplot_string("pantograph " + std::to_string(p) + ": " + s + " in the window")
     << "\nplot ";
  for (std::size_t k = 0; k < curves.size(); ++k)
    gp << (k ? ", \\\n  " : "") << curves[k];
  gp << '\n';
}

/// The Monte Carlo histograms of pantograph @p p.
void monte_carlo_script(std::ostream& gp, const std::string& csv, const std::string& png,
                        const SweepTable& t, const unsigned int p)
{
  const std::string f = has_filtered(t, p) ? "filtered_" : "";
  const std::vector<std::pair<std::string, std::string>> panels = {
      {f + "std", "sigma [N]"},
      {f + "max", "max [N]"},
      {f + "min", "min [N]"},
      {f + "mean", "mean [N]"},
      {"contact_loss_percent", "contact loss, raw [%]"},
      {"max_support_uplift_m", "max steady-arm uplift [m]"}};
  gp << terminal_for(png, 1200, 700) << "set multiplot layout 2,3 title "
     << gnuplot_string("pantograph " + std::to_string(p) + ": " +
                       std::to_string(sorted_values(t, p, 0).size()) + " samples" +
                       (f.empty() ? "" : " (forces after the low pass)"))
     << "\nset grid\nset style fill solid 0.5\nunset key\nset ylabel 'samples'\n";
  for (const auto& [s, label] : panels)
  {
    const std::vector<double> v = sorted_values(t, p, SweepTable::statistic(s));
    const double range = v.empty() ? 0. : v.back() - v.front();
    const double width =
        range > 0. ? range / 10. : std::max(std::abs(v.empty() ? 1. : v[0]) * 1e-3, 1e-9);
    gp << "set xlabel " << gnuplot_string(label) << "\nw = " << std::setprecision(10)
       << width << "\nbin(x) = w * floor(x / w) + w / 2\n"
       << "set boxwidth w * 0.9\nplot '" << checked_file_name(csv)
       << "' skip 1 using (bin(" << of_pantograph(p, csv_column(s, 1), 2)
       << ")):(1.0) smooth frequency with boxes\n";
  }
  gp << "unset multiplot\n";
}
} // namespace

unsigned int SweepTable::statistic(const std::string& name)
{
  const auto& c = sweep_statistic_columns();
  const auto it = std::find(c.begin(), c.end(), name);
  Assert(it != c.end(), dealii::ExcMessage("no statistic " + name));
  return it - c.begin();
}

std::vector<unsigned int> SweepTable::pantographs() const
{
  std::set<unsigned int> p;
  for (const Row& r : rows)
    p.insert(r.pantograph);
  return {p.begin(), p.end()};
}

SweepTable read_sweep_table(const std::string& csv, const unsigned int n_keys)
{
  SweepTable t;
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = split_row(line, n_keys);
  t.key_columns.assign(header.begin(), header.begin() + n_keys);
  const std::size_t n_statistics = sweep_statistic_columns().size();
  while (std::getline(in, line))
  {
    const std::vector<std::string> f = split_row(line, n_keys + 1 + n_statistics + 1);
    SweepTable::Row r;
    r.key.assign(f.begin(), f.begin() + n_keys);
    r.pantograph = static_cast<unsigned int>(to_value(f[n_keys]));
    for (std::size_t c = 0; c < n_statistics; ++c)
      r.values.push_back(to_value(f[n_keys + 1 + c]));
    r.status = f[n_keys + 1 + n_statistics];
    r.reason = f.back();
    t.rows.push_back(r);
  }
  return t;
}

std::string monte_carlo_distribution_csv(const SweepTable& t)
{
  std::ostringstream csv;
  csv << "statistic,pantograph,n,mean,std,min,p5,p50,p95,max\n" << std::setprecision(7);
  for (const unsigned int p : t.pantographs())
    for (const std::string& s : sweep_statistic_columns())
    {
      const Summary d = summarise(sorted_values(t, p, SweepTable::statistic(s)));
      csv << s << ',' << p << ',' << d.n;
      for (const double x : {d.mean, d.std, d.min, d.p5, d.p50, d.p95, d.max})
        if (d.n > 0)
          csv << ',' << x;
        else
          csv << ',';
      csv << '\n';
    }
  return csv.str();
}

void print_monte_carlo_summary(std::ostream& out, const SweepTable& t)
{
  out << std::fixed;
  for (const unsigned int p : t.pantographs())
  {
    const std::string f = has_filtered(t, p) ? "filtered_" : "";
    out << "  pantograph " << p << ", distribution over the completed samples:\n"
        << "    statistic" << std::setw(32) << "n" << std::setw(10) << "mean"
        << std::setw(10) << "std" << std::setw(10) << "p5" << std::setw(10) << "p50"
        << std::setw(10) << "p95" << std::setw(10) << "min" << std::setw(10) << "max\n";
    for (const std::string& s :
         {f + "mean", f + "std", f + "max", f + "min",
          std::string("contact_loss_percent"), std::string("max_support_uplift_m")})
    {
      const Summary d = summarise(sorted_values(t, p, SweepTable::statistic(s)));
      const int digits = s == "max_support_uplift_m" ? 5 : 2;
      out << "    " << std::left << std::setw(36) << s << std::right << std::setw(5)
          << d.n << std::setprecision(digits);
      for (const double x : {d.mean, d.std, d.p5, d.p50, d.p95, d.min, d.max})
        if (d.n > 0)
          out << std::setw(10) << x;
        else
          out << std::setw(10) << "-";
      out << '\n';
    }
    unsigned int lost = 0;
    for (const SweepTable::Row& r : t.rows)
      if (r.pantograph == p && r.status == "completed" &&
          r.values[SweepTable::statistic("contact_loss_percent")] > 0.)
      {
        out << (lost++ ? ", " : "    samples that lost contact (raw): ") << r.key[0]
            << " (" << std::setprecision(2)
            << r.values[SweepTable::statistic("contact_loss_percent")] << " %)";
      }
    out << (lost ? "\n" : "    no sample lost contact in the window\n");
  }
  for (const SweepTable::Row& r : t.rows)
    if (r.status != "completed" && r.pantograph == 1)
      out << "    sample " << r.key[0] << " " << r.status << ": " << r.reason << '\n';
  out << std::defaultfloat;
}

std::vector<std::string> plot_sweep(const std::string& dir, const std::string& name,
                                    const SweepKind kind, const SweepTable& t,
                                    const double wave_speed,
                                    const AssessmentCriteria* criteria,
                                    const std::string& key_unit)
{
  const std::string csv = name + ".csv";
  const std::vector<unsigned int> pantographs = t.pantographs();
  const bool several = pantographs.size() > 1;
  std::vector<std::string> drawn;
  for (const unsigned int p : pantographs)
  {
    std::vector<std::pair<std::string, std::string>> plots; // script, png
    if (kind == SweepKind::parameter)
      for (const std::string s :
           {"mean", "std", "max", "min", "mean_plus_3std", "mean_minus_3std",
            "contact_loss_percent", "max_support_uplift_m"})
        plots.emplace_back(s, png_name(name + "_" + s, p, several));
    else
      plots.emplace_back("", png_name(name, p, several));
    for (const auto& [statistic, png] : plots)
    {
      const std::string script = png.substr(0, png.size() - 4) + ".gp";
      {
        OutputFile gp(dir + "/" + script);
        begin_gnuplot_script(gp, script);
        gp << "set datafile separator ','\nset datafile missing ''\n";
        for (const std::string& file : {png, svg_file_of(png)}) // the same picture twice
          if (kind == SweepKind::speed)
            speed_script(gp, csv, file, t, p, wave_speed, criteria);
          else if (kind == SweepKind::parameter)
            parameter_script(gp, file, t, p, statistic, key_unit);
          else
            monte_carlo_script(gp, csv, file, t, p);
        gp.close();
      }
      for (const std::string& file : run_gnuplot(dir, script, {png, svg_file_of(png)}))
        drawn.push_back(file);
    }
  }
  return drawn;
}
} // namespace pantocat
