#pragma once

#include <string>
#include <vector>

namespace pantocat
{
/**
 * PNG plots of a time series CSV with gnuplot (Debian's gnuplot-nox), as in
 * the paper's Figs. 6 and 7: lambda_p, the dropper forces, and the pantograph
 * coordinates over time. Writes the gnuplot script next to the PNG files, so
 * `gnuplot time_series.gp` redraws them. Returns false (and writes only the
 * script) if gnuplot is not installed.
 */
bool plot_time_series(const std::string& directory, unsigned int n_droppers,
                      const std::vector<std::string>& pantograph_coordinates,
                      const std::string& title);
} // namespace pantocat
