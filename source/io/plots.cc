#include <pantocat/base/input_error.h>
#include <pantocat/io/external_program.h>
#include <pantocat/io/plots.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <fstream>

namespace pantocat
{
bool gnuplot_available()
{
  return !find_program("gnuplot").empty();
}

bool run_gnuplot(const std::string& dir, const std::string& script)
{
  const std::string gnuplot = find_program("gnuplot");
  // The script is a plain file name: a leading "./" keeps gnuplot from
  // reading one that starts with '-' as an option.
  return !gnuplot.empty() && run_program(gnuplot, {"./" + script}, dir);
}

std::string gnuplot_string(const std::string& text)
{
  std::string quoted = "'";
  for (const char c : text)
    if (c == '\'')
      quoted += "''";
    else
      quoted += static_cast<unsigned char>(c) < 0x20 || c == 0x7f ? ' ' : c;
  return quoted + "'";
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
       << "set title " << gnuplot_string(title + ": contact force and its statistics")
       << '\n';
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

bool plot_time_series(const std::string& dir, const unsigned int n_droppers,
                      const std::vector<std::string>& coordinates,
                      const std::string& title)
{
  const std::string script = dir + "/time_series.gp";
  {
    std::ofstream gp(script);
    gp << "# Redraw with: gnuplot time_series.gp (in this directory)\n"
       << "set datafile separator ','\n"
       << "set terminal pngcairo size 900,500 noenhanced\n"
       << "set grid\nset xlabel 't [s]'\nset key outside right\n"
       << "set output 'contact_force.png'\n"
       << "set title " << gnuplot_string(title + ": contact force")
       << "\nset ylabel 'lambda_p [N]'\n"
       << "plot 'time_series.csv' using 1:3 with lines title 'lambda_p'\n"
       << "set output 'dropper_forces.png'\n"
       << "set title " << gnuplot_string(title + ": dropper forces")
       << "\nset ylabel 'lambda_d [N]'\n"
       << "plot ";
    for (unsigned int j = 0; j < n_droppers; ++j)
      gp << (j ? ", " : "") << "'time_series.csv' using 1:" << 4 + j
         << " with lines title 'lambda_d" << j + 1 << "'";
    gp << "\nset output 'pantograph.png'\n"
       << "set title " << gnuplot_string(title + ": pantograph")
       << "\nset ylabel 'w [m]'\nplot ";
    for (unsigned int k = 0; k < coordinates.size(); ++k)
      gp << (k ? ", " : "") << "'time_series.csv' using 1:" << 4 + n_droppers + k
         << " with lines title " << gnuplot_string(coordinates[k]);
    gp << '\n';
  }
  return run_gnuplot(dir, "time_series.gp");
}
} // namespace pantocat
