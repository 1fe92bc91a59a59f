#pragma once

#include <pantocat/simulation/contact_statistics.h>

#include <string>
#include <vector>

namespace pantocat
{
/**
 * contact_force.png, dropper_forces.png and pantograph.png (Figs. 6 and 7)
 * from time_series.csv, whose header is @p columns: each plot draws the named
 * columns that exist (found by name, never by position). Writes
 * time_series.gp and returns false (drawing nothing) if one of the three
 * lists is empty or gnuplot fails.
 */
bool plot_time_series(const std::string& directory,
                      const std::vector<std::string>& columns,
                      const std::vector<std::string>& contact_forces,
                      const std::vector<std::string>& dropper_forces,
                      const std::vector<std::string>& coordinates,
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

/// True if gnuplot is on the PATH.
bool gnuplot_available();

/// Runs @p script (a file name in @p directory) with gnuplot inside @p directory;
/// false if gnuplot is not installed or fails.
bool run_gnuplot(const std::string& directory, const std::string& script);
} // namespace pantocat
