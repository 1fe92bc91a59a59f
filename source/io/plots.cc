#include <pantocat/base/input_error.h>
#include <pantocat/io/plots.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>

namespace pantocat
{
bool gnuplot_available()
{
  return std::system("command -v gnuplot > /dev/null 2>&1") == 0;
}

bool run_gnuplot(const std::string& dir, const std::string& script)
{
  if (!gnuplot_available())
    return false;
  const std::string command = "cd '" + dir + "' && gnuplot '" + script + "' 2> /dev/null";
  return std::system(command.c_str()) == 0;
}

bool plot_contact_force_statistics(const std::string& dir,
                                   const ContactForceStatistics& s,
                                   const std::string& title)
{
  const std::string script = "contact_force_statistics.gp";
  {
    std::ofstream gp(dir + "/" + script);
    gp << "# Redraw with: gnuplot " << script << " (in this directory)\n"
       << "set datafile separator ','\n"
       << "set terminal pngcairo size 900,500 noenhanced\n"
       << "set output 'contact_force_statistics.png'\n"
       << "set grid\nset autoscale xfix\nset offsets 0, 0, graph 0.05, graph 0.05\nset "
          "key outside right\n"
       << "set xlabel 'x_p [m]'\nset ylabel 'lambda_p [N]'\n"
       << "set title '" << title << ": contact force and its statistics'\n";
    const bool window = s.n_points > 0; // else: no statistics to draw
    if (window)
      for (const double x : {s.window_start, s.window_end})
        gp << "set arrow from " << x << ", graph 0 to " << x
           << ", graph 1 nohead dashtype 3\n";
    gp << "plot 'contact_force.csv' using 2:3 with lines lc rgb '#b0b0b0' title "
          "'lambda_p'";
    if (s.filter_cutoff_hz > 0.)
      gp << ", 'contact_force.csv' using 2:4 with lines lc rgb '#0060c0' title 'low pass "
         << s.filter_cutoff_hz << " Hz'";
    if (window)
      gp << ", " << s.mean << " with lines lc rgb 'black' title 'mean'"
         << ", " << s.mean_plus_3_sigma
         << " with lines dashtype 2 lc rgb '#c00000' title 'mean + 3 sigma'"
         << ", " << s.mean_minus_3_sigma
         << " with lines dashtype 2 lc rgb '#c00000' title 'mean - 3 sigma'";
    gp << '\n';
    if (!gp)
      throw SimulationError("cannot write " + dir + "/" + script);
  }
  return run_gnuplot(dir, script);
}

namespace
{
/// 1-based column of @p name in @p columns, or 0.
std::size_t column_of(const std::vector<std::string>& columns, const std::string& name)
{
  const auto it = std::find(columns.begin(), columns.end(), name);
  return it == columns.end() ? 0 : it - columns.begin() + 1;
}

/// "plot 'time_series.csv' using 1:c title 'name', ..." for the @p names that exist.
void plot_columns(std::ostream& gp, const std::vector<std::string>& columns,
                  const std::vector<std::string>& names)
{
  gp << "plot ";
  bool first = true;
  for (const std::string& name : names)
    if (const std::size_t c = column_of(columns, name))
    {
      gp << (first ? "" : ", ") << "'time_series.csv' using 1:" << c
         << " with lines title '" << name << "'";
      first = false;
    }
  gp << '\n';
}
} // namespace

bool plot_time_series(const std::string& dir, const std::vector<std::string>& columns,
                      const std::vector<std::string>& contact_forces,
                      const std::vector<std::string>& dropper_forces,
                      const std::vector<std::string>& coordinates,
                      const std::string& title)
{
  if (contact_forces.empty() || dropper_forces.empty() || coordinates.empty())
    return false; // nothing to draw in one of the three plots
  const std::string script = dir + "/time_series.gp";
  {
    std::ofstream gp(script);
    gp << "# Redraw with: gnuplot time_series.gp (in this directory)\n"
       << "set datafile separator ','\n"
       << "set terminal pngcairo size 900,500 noenhanced\n"
       << "set grid\nset xlabel 't [s]'\nset key outside right\n"
       << "set output 'contact_force.png'\n"
       << "set title '" << title << ": contact force'\nset ylabel 'lambda_p [N]'\n";
    plot_columns(gp, columns, contact_forces);
    gp << "set output 'dropper_forces.png'\n"
       << "set title '" << title << ": dropper forces'\nset ylabel 'lambda_d [N]'\n";
    plot_columns(gp, columns, dropper_forces);
    gp << "set output 'pantograph.png'\n"
       << "set title '" << title << ": pantograph'\nset ylabel 'w [m]'\n";
    plot_columns(gp, columns, coordinates);
  }
  return run_gnuplot(dir, "time_series.gp");
}
} // namespace pantocat
