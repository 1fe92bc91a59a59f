#include <pantocat/io/plots.h>

#include <cstdlib>
#include <fstream>

namespace pantocat
{
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
       << "set title '" << title << ": contact force'\nset ylabel 'lambda_p [N]'\n"
       << "plot 'time_series.csv' using 1:3 with lines title 'lambda_p'\n"
       << "set output 'dropper_forces.png'\n"
       << "set title '" << title << ": dropper forces'\nset ylabel 'lambda_d [N]'\n"
       << "plot ";
    for (unsigned int j = 0; j < n_droppers; ++j)
      gp << (j ? ", " : "") << "'time_series.csv' using 1:" << 4 + j
         << " with lines title 'lambda_d" << j + 1 << "'";
    gp << "\nset output 'pantograph.png'\n"
       << "set title '" << title << ": pantograph'\nset ylabel 'w [m]'\nplot ";
    for (unsigned int k = 0; k < coordinates.size(); ++k)
      gp << (k ? ", " : "") << "'time_series.csv' using 1:" << 4 + n_droppers + k
         << " with lines title '" << coordinates[k] << "'";
    gp << '\n';
  }
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0)
    return false;
  const std::string command = "cd '" + dir + "' && gnuplot time_series.gp 2> /dev/null";
  return std::system(command.c_str()) == 0;
}
} // namespace pantocat
