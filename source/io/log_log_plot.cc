#include <pantocat/io/log_log_plot.h>
#include <pantocat/io/plots.h>

#include <pantocat/base/safe_files.h>

namespace pantocat
{
bool plot_log_log(const std::string& dir, const std::string& name,
                  const std::string& title, const std::string& x_label,
                  const std::string& y_label, const std::vector<LogLogCurve>& curves,
                  const double target)
{
  const std::string script = name + ".gp";
  {
    OutputFile gp(dir + "/" + script);
    begin_gnuplot_script(gp, script);
    gp << "set terminal pngcairo size 1150,650 noenhanced\n"
       << "set colorsequence podo\n"
       << gnuplot_output(name + ".png") << '\n'
       << "set logscale xy\nset format x '%g'\nset format y '%.0e'\n"
       << "set grid xtics ytics mxtics mytics\nset key outside right font ',10'\n"
       << "set title " << gnuplot_string(title) << "\nset xlabel "
       << gnuplot_string(x_label) << "\nset ylabel " << gnuplot_string(y_label) << '\n';
    gp.precision(10);
    std::vector<std::size_t> drawn;
    for (std::size_t c = 0; c < curves.size(); ++c)
    {
      gp << "$curve" << c << " << EOD\n";
      bool any = false;
      for (const auto& [x, y] : curves[c].points)
        if (x > 0. && y > 0.)
          gp << x << ' ' << y << '\n', any = true;
      gp << "EOD\n";
      if (any)
        drawn.push_back(c);
    }
    gp << "plot ";
    for (std::size_t i = 0; i < drawn.size(); ++i)
      gp << (i ? ", " : "") << "$curve" << drawn[i]
         << " using 1:2 with linespoints title "
         << gnuplot_string(curves[drawn[i]].title);
    if (target > 0.)
      gp << (drawn.empty() ? "" : ", ") << target
         << " with lines dashtype 2 lc 'black' title 'target " << target << "'";
    else if (drawn.empty())
      gp << "1/0 notitle";
    gp << '\n';
    gp.close();
  }
  return !run_gnuplot(dir, script, {name + ".png"}).empty();
}
} // namespace pantocat
