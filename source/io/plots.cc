#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>
#include <pantocat/base/safe_files.h>
#include <pantocat/io/external_program.h>
#include <pantocat/io/plot_data.h>
#include <pantocat/io/plots.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace pantocat
{
namespace
{
/// Bins of envelope() per plot: two per pixel of the widest plot (1200 pixels).
constexpr unsigned int envelope_bins = 2400;

/**
 * read_csv_columns(), or empty columns if the file cannot be read: a plot
 * that cannot get its data is not drawn (gnuplot finds no points, and the run
 * reports the plot missing); the results already written stand.
 */
std::vector<std::vector<double>> curves_of(const std::string& csv,
                                           const std::vector<std::size_t>& wanted)
{
  try
  {
    return read_csv_columns(csv, wanted);
  }
  catch (const SimulationError&)
  {
    return std::vector<std::vector<double>>(wanted.size());
  }
}

/// 1-based column of @p name in @p columns, or 0.
std::size_t column_of(const std::vector<std::string>& columns, const std::string& name)
{
  const auto it = std::find(columns.begin(), columns.end(), name);
  return it == columns.end() ? 0 : it - columns.begin() + 1;
}
} // namespace

bool gnuplot_available()
{
  return !find_program("gnuplot").empty();
}

std::vector<std::string> run_gnuplot(const std::string& dir,
                                     const std::vector<PlotScript>& scripts)
{
  std::vector<std::string> outputs;
  for (const PlotScript& s : scripts)
    for (const std::string& file : s.outputs)
    {
      remove_output(dir + "/" + checked_file_name(file)); // no plot of an earlier run
      outputs.push_back(file);
    }
  const std::string gnuplot = find_program("gnuplot");
  if (gnuplot.empty() || scripts.empty())
    return {};
  // gnuplot writes into a directory of this process only (a link planted at
  // a plot's name is not followed); the plots are then renamed into place.
  const PrivateDirectory plots(dir);
  const std::vector<std::string> prefix{"-e", std::string(gnuplot_output_directory) +
                                                  " = '" + plots.name() + "/'"};
  std::vector<std::string> arguments = prefix;
  for (const PlotScript& s : scripts)
    // A plain file name: a leading "./" keeps gnuplot from reading one that
    // starts with '-' as an option.
    arguments.push_back("./" + checked_file_name(s.script));
  const auto missing = [&](const PlotScript& s)
  {
    return std::any_of(s.outputs.begin(), s.outputs.end(),
                       [&](const std::string& png) { return plots.size_of(png) == 0; });
  };
  // One gnuplot for all scripts (one start, not one per script). gnuplot
  // stops at the first script that fails: then each script whose plots are
  // missing runs again alone, so that one failure costs only its own plots.
  if (!run_program(gnuplot, arguments, dir) && scripts.size() > 1)
    for (const PlotScript& s : scripts)
      if (missing(s))
      {
        arguments = prefix;
        arguments.push_back("./" + s.script);
        run_program(gnuplot, arguments, dir);
      }
  std::vector<std::string> written;
  for (const std::string& file : outputs)
    if (plots.size_of(file) > 0 && plots.move_out(file, dir + "/" + file))
      written.push_back(file);
  return written;
}

std::vector<std::string> run_gnuplot(const std::string& dir, const std::string& script,
                                     const std::vector<std::string>& outputs)
{
  return run_gnuplot(dir, std::vector<PlotScript>{{script, outputs}});
}

std::string gnuplot_string(const std::string& text)
{
  std::string quoted = "'";
  for (const char c : text)
  {
    const auto u = static_cast<unsigned char>(c);
    const bool plain =
        std::isalnum(u) || u >= 0x80 ||
        std::string(" +-*/=_.,:;()[]<>%#!?&|~^{}").find(c) != std::string::npos;
    quoted += plain ? c : u < 0x20 || u == 0x7f ? ' ' : '_';
  }
  return quoted + "'";
}

void begin_gnuplot_script(std::ostream& gp, const std::string& script,
                          const std::string& comment)
{
  gp << "# Redraw with: gnuplot " << checked_file_name(script) << " (in this directory)\n"
     << comment << "if (!exists('" << gnuplot_output_directory << "')) "
     << gnuplot_output_directory << " = ''\n"
     << "reset # the settings of a script drawn before this one in the same gnuplot\n";
}

std::string gnuplot_output(const std::string& file)
{
  return std::string("set output ") + gnuplot_output_directory + ".'" +
         checked_file_name(file) + "'";
}

std::string svg_file_of(const std::string& png)
{
  const std::size_t dot = png.rfind('.');
  return (dot == std::string::npos ? png : png.substr(0, dot)) + ".svg";
}

std::string svg_copy(const std::string& png, const unsigned int width,
                     const unsigned int height, const std::string& terminal)
{
  return "set terminal svg size " + std::to_string(width) + "," + std::to_string(height) +
         " noenhanced font 'sans,12' background rgb 'white'\n" +
         gnuplot_output(svg_file_of(png)) + "\nreplot\nunset output\n" + terminal + "\n";
}

bool plot_contact_force_statistics(const std::string& dir,
                                   const ContactForceStatistics& s,
                                   const std::string& title)
{
  return !run_gnuplot(dir, {contact_force_statistics_script(dir, s, title)}).empty();
}

PlotScript contact_force_statistics_script(const std::string& dir,
                                           const ContactForceStatistics& s,
                                           const std::string& title)
{
  const std::string script = "contact_force_statistics.gp";
  // The lines of the figures the run reports first: filtered if filtered.
  const ForceFigures& f = s.filtered ? *s.filtered : s.raw;
  {
    OutputFile gp(dir + "/" + script);
    begin_gnuplot_script(gp, script,
                         "# The curves of contact_force.csv, kept as they are drawn: per "
                         "half pixel\n# the lowest and the highest point.\n");
    gp << "set terminal pngcairo size 900,500 noenhanced\n"
       << gnuplot_output("contact_force_statistics.png") << '\n'
       << "set grid\nset autoscale xfix\nset offsets 0, 0, graph 0.05, graph 0.05\nset "
          "key outside right\n"
       << "set xlabel 'pantograph position x_p [m]'\nset ylabel 'contact force lambda_p "
          "[N]'\n"
       << "set title " << gnuplot_string(title + ": contact force and its statistics")
       << '\n';
    const bool window = f.n_points > 0; // else: no statistics to draw
    if (window)
      for (const double x : {s.first_position, s.last_position})
        gp << "set arrow from " << x << ", graph 0 to " << x
           << ", graph 1 nohead dashtype 3\n";
    // The first contact's x_p, lambda_p and lambda_p_filtered are columns 2 to 4.
    const auto data = curves_of(dir + "/contact_force.csv",
                                s.filtered ? std::vector<std::size_t>{2, 3, 4}
                                           : std::vector<std::size_t>{2, 3});
    write_datablock(gp, "raw", envelope(data[0], data[1], envelope_bins));
    if (s.filtered)
      write_datablock(gp, "filtered", envelope(data[0], data[2], envelope_bins));
    gp << "plot $raw using 1:2 with lines lc rgb '#b0b0b0' title 'contact force'";
    if (s.filtered)
      gp << ", $filtered using 1:2 with lines lc rgb '#0060c0' title 'low pass "
         << s.filter_cutoff_hz << " Hz'";
    if (window)
      gp << ", " << f.mean << " with lines lc rgb 'black' title 'mean'"
         << ", " << f.mean_plus_3std
         << " with lines dashtype 2 lc rgb '#c00000' title 'mean + 3 std'"
         << ", " << f.mean_minus_3std
         << " with lines dashtype 2 lc rgb '#c00000' title 'mean - 3 std'";
    gp << '\n';
    gp.close();
  }
  return {script, {"contact_force_statistics.png"}};
}

std::string contact_force_over_x_file(const std::string& name, const bool several)
{
  if (!several)
    return "contact_force_over_x.png";
  std::string file = "contact_force_over_x_";
  for (const char c : name)
    file += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return file + ".png";
}

void mark_supports(std::ostream& gp, const std::vector<double>& supports, const double x0,
                   const double x1)
{
  for (std::size_t k = 0; k < supports.size(); ++k)
  {
    if (supports[k] >= x0 && supports[k] <= x1)
      gp << "set arrow from first " << supports[k] << ", graph 0 to first " << supports[k]
         << ", graph 1 nohead dashtype 2 lc rgb '#707070'\n";
    const double middle =
        k + 1 < supports.size() ? 0.5 * (supports[k] + supports[k + 1]) : x1 + 1.;
    if (middle > x0 && middle < x1)
      gp << "set label 'span " << k + 1 << "' at first " << middle
         << ", graph 0.96 center tc rgb '#505050'\n";
  }
}

void shade_window(std::ostream& gp, const EvaluationWindow& w, const double x0,
                  const double x1)
{
  if (w.whole_run())
    return;
  const double a = std::max(w.start, x0), b = std::min(w.end, x1);
  if (a < b)
    gp << "set object rectangle from first " << a << ", graph 0 to first " << b
       << ", graph 1 behind fillcolor rgb '#e4ecf8' fillstyle solid 1.0 noborder\n";
}

namespace
{
constexpr const char* over_x_terminal = "set terminal pngcairo size 1200,500 noenhanced";

/// A force level drawn across the window: a limit of the assessment or the window's F_m.
struct ForceLimit
{
  std::string label, colour;
  double value;
  int dash; ///< gnuplot dashtype
  bool below =
      false; ///< label under the line at the window's start (else above, at its end)
};

/// The window's F_m and the force limits of @p p's assessment (none without one).
std::vector<ForceLimit> force_limits(const ForceOverXPlot& p)
{
  std::vector<ForceLimit> limits;
  const ContactForceStatistics& s = *p.statistics;
  const ForceFigures& f = s.filtered ? *s.filtered : s.raw;
  if (s.window.whole_run() || f.n_points == 0)
    return limits;
  limits.push_back(
      {"F_m " + number_to_string(f.mean, 4) + " N", "#000000", f.mean, 1, true});
  if (p.assessment == nullptr)
    return limits;
  for (const CriterionResult& c : p.assessment->criteria)
  {
    const std::string value = number_to_string(c.limit, 4) + " N";
    if (c.name == "mean_force")
      limits.push_back({"target F_m " + value, "#008000", c.limit, 2});
    else if (c.name == "max_force")
      limits.push_back({"limit F_max " + value, "#c00000", c.limit, 2});
    else if (c.name == "statistical_minimum")
      limits.push_back({"F_m - 3 sigma > " + value, "#c00000", c.limit, 3});
  }
  return limits;
}

/// @p limits as labelled horizontal lines over the window of @p s.
void draw_limits(std::ostream& gp, const std::vector<ForceLimit>& limits,
                 const ContactForceStatistics& s)
{
  for (const ForceLimit& l : limits)
    gp << "set arrow from first " << s.first_position << ", first " << l.value
       << " to first " << s.last_position << ", first " << l.value
       << " nohead front lw 1.5 dashtype " << l.dash << " lc rgb '" << l.colour << "'\n"
       << "set label " << gnuplot_string(l.label) << " at first "
       << (l.below ? s.first_position : s.last_position) << ", first " << l.value
       << (l.below ? " left offset 0.5,-0.6" : " right offset -0.5,0.6")
       << " front tc rgb '" << l.colour << "'\n";
}

/// One pantograph's page of contact_force_over_x.gp.
void plot_over_x(std::ostream& gp, const ForceOverXPlot& p, const std::string& csv,
                 const std::vector<std::string>& columns,
                 const std::vector<double>& supports, const std::string& title)
{
  const ContactForceStatistics& s = *p.statistics;
  gp << "unset arrow\nunset label\nunset object\n"
     << gnuplot_output(p.png) << '\n'
     << "set title "
     << gnuplot_string(title + ": contact force over x_p, " + p.name + ", window " +
                       s.window.describe())
     << '\n'
     << "set xrange [" << p.x_begin << ':' << p.x_end << "]\n";
  // The force axis is the window's (and its limits'): a spike outside it
  // (the arrival at an anchor) is clipped instead of squeezing the window's trace.
  const std::vector<ForceLimit> limits = force_limits(p);
  if (!s.window.whole_run() && s.raw.max > s.raw.min)
  {
    double low = std::min(0., s.raw.min), high = s.raw.max;
    for (const ForceLimit& l : limits)
      low = std::min(low, l.value), high = std::max(high, l.value);
    const double range = high - low;
    gp << "set yrange [" << low - 0.05 * range << ':' << high + 0.15 * range << "]\n";
  }
  else
    gp << "set yrange [*:*]\n";
  mark_supports(gp, supports, p.x_begin, p.x_end);
  shade_window(gp, s.window, p.x_begin, p.x_end);
  draw_limits(gp, limits, s);
  const auto column = [&](const std::string& name)
  { return column_of(columns, name + p.suffix); };
  std::vector<std::size_t> wanted{column("x_p"), column("lambda_p")};
  if (s.filtered)
    wanted.push_back(column("lambda_p_filtered"));
  const auto data = curves_of(csv, wanted);
  write_datablock(gp, "raw", envelope(data[0], data[1], envelope_bins));
  if (s.filtered)
    write_datablock(gp, "filtered", envelope(data[0], data[2], envelope_bins));
  gp << "plot $raw using 1:2 with lines lc rgb '#a0a0a0' title 'contact force (raw)'";
  if (s.filtered)
    gp << ", $filtered using 1:2 with lines lw 1.5 lc rgb '#0060c0' title "
       << gnuplot_string("low pass " + number_to_string(s.filter_cutoff_hz, 4) +
                         " Hz (order " + std::to_string(s.filter_order) + ")");
  gp << '\n' << svg_copy(p.png, 1000, 420, over_x_terminal);
}
} // namespace

std::vector<std::string>
plot_contact_force_over_x(const std::string& dir, const std::vector<std::string>& columns,
                          const std::vector<ForceOverXPlot>& plots,
                          const std::vector<double>& supports, const std::string& title)
{
  if (plots.empty())
    return {};
  return run_gnuplot(dir,
                     {contact_force_over_x_script(dir, columns, plots, supports, title)});
}

PlotScript contact_force_over_x_script(const std::string& dir,
                                       const std::vector<std::string>& columns,
                                       const std::vector<ForceOverXPlot>& plots,
                                       const std::vector<double>& supports,
                                       const std::string& title)
{
  std::vector<std::string> pngs;
  for (const ForceOverXPlot& p : plots)
  {
    pngs.push_back(p.png);
    pngs.push_back(svg_file_of(p.png));
  }
  const std::string script = "contact_force_over_x.gp";
  {
    OutputFile gp(dir + "/" + script);
    begin_gnuplot_script(
        gp, script,
        "# Shaded: the evaluation window; dashed: the supports; across the window: its\n"
        "# F_m and the assessment's force limits. The force axis spans the window's raw\n"
        "# force and the limits (a spike outside the window is clipped). The curves of\n"
        "# contact_force.csv, kept as they are drawn: per half pixel the lowest and\n"
        "# the highest point.\n");
    gp << over_x_terminal << '\n'
       << "set grid ytics\nset key below horizontal\nset offsets 0, 0, graph 0.08, graph "
          "0.05\n"
       << "set xlabel 'pantograph position x_p [m]'\nset ylabel 'contact force lambda_p "
          "[N]'\n";
    for (const ForceOverXPlot& p : plots)
      plot_over_x(gp, p, dir + "/contact_force.csv", columns, supports, title);
    gp.close();
  }
  return {script, pngs};
}

namespace
{

/**
 * The curves the plots draw, read from time_series.csv (@p columns, time
 * first) and written into the script as the datablocks $c1, $c2, ... in the
 * order of @p names, each reduced by envelope(). gnuplot then neither parses
 * the wide CSV (one column per dropper, 18 MB for two pantographs on 13
 * spans) nor draws more points than the picture shows.
 */
void write_plotted_columns(std::ostream& gp, const std::string& csv,
                           const std::vector<std::string>& columns,
                           const std::vector<std::string>& names)
{
  std::vector<std::size_t> wanted{1};
  for (const std::string& name : names)
    wanted.push_back(column_of(columns, name));
  const auto data = curves_of(csv, wanted);
  for (std::size_t k = 0; k < names.size(); ++k)
    write_datablock(gp, "c" + std::to_string(k + 1),
                    envelope(data[0], data[k + 1], envelope_bins));
}

/// "plot $ck using 1:2 title 'name', ..." for the @p names, whose
/// datablocks are numbered by their place in @p plotted.
void plot_columns(std::ostream& gp, const std::vector<std::string>& plotted,
                  const std::vector<std::string>& names)
{
  gp << "plot ";
  bool first = true;
  for (const std::string& name : names)
  {
    gp << (first ? "" : ", ") << "$c" << column_of(plotted, name)
       << " using 1:2 with lines title " << gnuplot_string(name);
    first = false;
  }
  gp << '\n';
}
} // namespace

std::vector<std::string> plot_time_series(const std::string& dir,
                                          const std::vector<std::string>& columns,
                                          const std::vector<std::string>& contact_forces,
                                          const std::vector<std::string>& dropper_forces,
                                          const std::vector<std::string>& coordinates,
                                          const std::string& title)
{
  const PlotScript script = time_series_script(dir, columns, contact_forces,
                                               dropper_forces, coordinates, title);
  if (script.outputs.empty())
    return {}; // nothing to draw
  return run_gnuplot(dir, {script});
}

PlotScript time_series_script(const std::string& dir,
                              const std::vector<std::string>& columns,
                              const std::vector<std::string>& contact_forces,
                              const std::vector<std::string>& dropper_forces,
                              const std::vector<std::string>& coordinates,
                              const std::string& title)
{
  struct Plot
  {
    std::string png, what, ylabel;
    std::vector<std::string> names; ///< of the columns that exist
  };
  std::vector<Plot> plots{
      {"contact_force.png", "contact force", "contact force lambda_p [N]", {}},
      {"dropper_forces.png", "dropper forces", "dropper force lambda_d [N]", {}},
      {"pantograph.png", "pantograph", "pantograph displacement w [m]", {}}};
  const std::vector<std::string>* lists[] = {&contact_forces, &dropper_forces,
                                             &coordinates};
  for (unsigned int i = 0; i < plots.size(); ++i)
    for (const std::string& name : *lists[i])
      if (column_of(columns, name) > 0)
        plots[i].names.push_back(name);
  plots.erase(std::remove_if(plots.begin(), plots.end(),
                             [](const Plot& plot) { return plot.names.empty(); }),
              plots.end());
  const std::string script = "time_series.gp";
  if (plots.empty())
    return {script, {}}; // nothing to draw
  {
    OutputFile gp(dir + "/" + script);
    begin_gnuplot_script(gp, script,
                         "# The curves of time_series.csv, kept as they are drawn: per "
                         "half pixel\n# the lowest and the highest point.\n");
    gp << "set terminal pngcairo size 900,500 noenhanced\n"
       << "set grid\nset xlabel 'time t [s]'\nset key outside right\n";
    std::vector<std::string> plotted;
    for (const Plot& plot : plots)
      plotted.insert(plotted.end(), plot.names.begin(), plot.names.end());
    write_plotted_columns(gp, dir + "/time_series.csv", columns, plotted);
    for (const Plot& plot : plots)
    {
      gp << gnuplot_output(plot.png) << "\n"
         << "set title " << gnuplot_string(title + ": " + plot.what) << "\n"
         << "set ylabel '" << plot.ylabel << "'\n";
      plot_columns(gp, plotted, plot.names);
    }
    gp.close();
  }
  std::vector<std::string> pngs;
  for (const Plot& plot : plots)
    pngs.push_back(plot.png);
  return {script, pngs};
}
} // namespace pantocat
