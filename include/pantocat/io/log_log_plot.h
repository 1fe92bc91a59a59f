#pragma once

#include <string>
#include <utility>
#include <vector>

namespace pantocat
{
/// One curve of a log-log plot: (x, y) points, drawn in the given order.
struct LogLogCurve
{
  std::string title;
  std::vector<std::pair<double, double>> points;
};

/**
 * A log-log plot with gnuplot (as plot_time_series): writes
 * `<directory>/<name>.gp` with the data inline, so `gnuplot <name>.gp` redraws
 * `<name>.png`. Points with a non-positive coordinate are left out (a log axis
 * cannot show them); @p target > 0 adds a dashed horizontal line at that
 * value. Returns false (only the script written) if gnuplot is
 * not installed or fails.
 */
bool plot_log_log(const std::string& directory, const std::string& name,
                  const std::string& title, const std::string& x_label,
                  const std::string& y_label, const std::vector<LogLogCurve>& curves,
                  double target = 0.);
} // namespace pantocat
