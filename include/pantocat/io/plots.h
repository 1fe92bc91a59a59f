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
 * contact_force_statistics.png: lambda_p over x_p from contact_force.csv
 * (columns t, x_p, lambda_p, lambda_p_filtered), the filtered force when a
 * cut-off is set, and horizontal lines at the mean and mean +/- 3 sigma of
 * @p statistics, whose window is marked. Script: contact_force_statistics.gp.
 */
bool plot_contact_force_statistics(const std::string& directory,
                                   const ContactForceStatistics& statistics,
                                   const std::string& title);

/// True if gnuplot is on the PATH (looked up without a shell: find_program()).
bool gnuplot_available();

/**
 * Runs @p script (a file name in @p directory) with gnuplot inside @p
 * directory, without a shell (run_program()): the directory's name may hold
 * any character. False if gnuplot is not installed or fails.
 */
bool run_gnuplot(const std::string& directory, const std::string& script);

/**
 * @p text as a single-quoted gnuplot string: quotes doubled, control
 * characters (a newline would end the command) replaced by spaces.
 */
std::string gnuplot_string(const std::string& text);
} // namespace pantocat
