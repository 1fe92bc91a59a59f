#include <pantocat/base/safe_files.h>
#include <pantocat/io/line_response_plots.h>

#include <algorithm>
#include <iomanip>

namespace pantocat
{
namespace
{
constexpr const char* terminal = "set terminal pngcairo size 1200,450 noenhanced";

/// The first lines of a plot along the line: terminal, output, axes, supports, window.
void begin_line_plot(std::ostream& gp, const std::string& png,
                     const LineResponseFrame& frame, const EvaluationWindow& window,
                     const std::string& what)
{
  const double x0 = frame.supports.empty() ? 0. : frame.supports.front();
  const double x1 = frame.supports.empty() ? 1. : frame.supports.back();
  gp << terminal << '\n'
     << gnuplot_output(png) << '\n'
     << "set grid ytics\nset key below horizontal\n"
     << "set xlabel 'position along the line x [m]'\n"
     << "set xrange [" << x0 << ':' << x1 << "]\n"
     << "set title " << gnuplot_string(frame.title + ": " + what) << '\n'
     << std::setprecision(10);
  mark_supports(gp, frame.supports, x0, x1);
  shade_window(gp, window, x0, x1);
}

/// The steady-arm limit [m] of @p a, or a negative number without one.
double uplift_limit(const Assessment* a)
{
  if (a != nullptr)
    for (const CriterionResult& c : a->criteria)
      if (c.name == "steady_arm_uplift")
        return c.limit;
  return -1.;
}
} // namespace

PlotScript uplift_script(const std::string& dir, const ContactForceStatistics& s,
                         const std::vector<double>& droppers,
                         const Assessment* assessment, const LineResponseFrame& frame)
{
  const std::string script = "uplift.gp", png = "uplift.png";
  const bool at_droppers = !s.max_uplift_at_droppers.empty();
  if (!at_droppers && s.steady_arms.empty())
    return {script, {}};
  OutputFile gp(dir + "/" + script);
  begin_gnuplot_script(
      gp, script,
      "# Uplift: the largest rise of the contact wire over its height at "
      "t = 0.\n");
  begin_line_plot(gp, png, frame, s.window, "uplift of the contact wire");
  gp << "set ylabel 'uplift [mm]'\nset yrange [0:*]\n";
  const double limit = uplift_limit(assessment);
  if (limit > 0.) // the y-range reaches above the limit line
    gp << "set yrange [0:" << 1.15e3 * limit << "<*]\n"
       << "set arrow from graph 0, first " << 1e3 * limit << " to graph 1, first "
       << 1e3 * limit << " nohead front lw 1.5 dashtype 2 lc rgb '#c00000'\n"
       << "set label "
       << gnuplot_string("limit " + std::to_string(int(1e3 * limit)) +
                         " mm at the steady arms")
       << " at graph 1, first " << 1e3 * limit
       << " right offset -0.5,0.6 front tc rgb '#c00000'\n";
  gp << "$droppers << EOD\n";
  for (std::size_t j = 0; j < s.max_uplift_at_droppers.size() && j < droppers.size(); ++j)
    gp << droppers[j] << ' ' << 1e3 * s.max_uplift_at_droppers[j] << '\n';
  gp << "EOD\n$arms << EOD\n";
  for (const SteadyArmUplift& a : s.steady_arms)
    gp << a.x << ' ' << 1e3 * a.max_uplift << '\n';
  gp << "EOD\nplot $droppers using 1:2 with points pt 7 ps 0.6 lc rgb '#808080' title "
        "'at the droppers, whole run'";
  if (!s.steady_arms.empty())
    gp << ", $arms using 1:2 with impulses lw 4 lc rgb '#0060c0' title 'at the steady "
          "arms in the window', $arms using 1:2 with points pt 7 lc rgb '#0060c0' "
          "notitle";
  gp << '\n' << svg_copy(png, 1000, 380, terminal);
  gp.close();
  return {script, {png, svg_file_of(png)}};
}

PlotScript dropper_slack_script(const std::string& dir,
                                const std::vector<double>& droppers,
                                const std::vector<std::vector<Interval>>& slack,
                                const EvaluationWindow& window,
                                const LineResponseFrame& frame)
{
  const std::string script = "dropper_slack.gp", png = "dropper_slack.png";
  if (droppers.empty() || slack.size() != droppers.size())
    return {script, {}};
  OutputFile gp(dir + "/" + script);
  begin_gnuplot_script(gp, script,
                       "# Per dropper: the time it was slack in the whole run and the "
                       "number of its slack intervals.\n");
  begin_line_plot(gp, png, frame, window, "dropper slack over the whole run");
  std::size_t intervals = 0;
  gp << "$slack << EOD\n";
  for (std::size_t j = 0; j < droppers.size(); ++j)
  {
    double slack_time = 0.;
    for (const Interval& i : slack[j])
      slack_time += i.second - i.first;
    intervals += slack[j].size();
    gp << droppers[j] << ' ' << 1e3 * slack_time << ' ' << slack[j].size() << '\n';
  }
  gp << "EOD\nset ylabel 'time slack [ms]'\n";
  if (intervals == 0) // gnuplot refuses a curve without a defined point
    gp << "set yrange [0:1]\nplot $slack using 1:2 with impulses lc rgb '#c06000' "
          "title 'no dropper went slack'\n";
  else
    gp << "set y2label 'slack intervals'\nset yrange [0:*]\nset y2range [0:*]\n"
       << "set ytics nomirror\nset y2tics\nplot $slack using 1:2 with impulses lw 3 lc "
          "rgb '#c06000' title 'time slack [ms]', $slack using 1:($3 > 0 ? $3 : NaN) "
          "axes x1y2 with points pt 6 lc rgb 'black' title 'slack intervals'\n";
  gp << svg_copy(png, 1000, 380, terminal);
  gp.close();
  return {script, {png, svg_file_of(png)}};
}
} // namespace pantocat
