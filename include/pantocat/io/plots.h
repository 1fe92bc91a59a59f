#pragma once

#include <pantocat/simulation/contact_statistics.h>

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

/**
 * A log-log PNG of columns of a CSV file with a header row (for studies:
 * errors or run times against step size or grid size): @p y_columns against
 * @p x_column, points joined by lines, named by their headers. Writes the
 * gnuplot script next to the PNG (`<png without .png>.gp`; both in
 * @p directory, the CSV file name relative to it) and runs it. Returns false
 * (script only) if gnuplot is not installed; throws SimulationError if the
 * CSV file cannot be read or lacks a column.
 */
bool plot_loglog(const std::string& directory, const std::string& csv,
                 const std::string& x_column, const std::vector<std::string>& y_columns,
                 const std::string& title, const std::string& png);

/**
 * contact_force_statistics.png: lambda_p over x_p from contact_force.csv
 * (columns t, x_p, lambda_p, lambda_p_filtered), the filtered force when a
 * cut-off is set, and horizontal lines at the mean and mean +/- 3 sigma of
 * @p statistics, whose window is marked. Script: contact_force_statistics.gp.
 */
bool plot_contact_force_statistics(const std::string& directory,
                                   const ContactForceStatistics& statistics,
                                   const std::string& title);

/// True if gnuplot is on the PATH.
bool gnuplot_available();
} // namespace pantocat
