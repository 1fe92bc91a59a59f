#pragma once

#include <pantocat/simulation/contact_statistics.h>

#include <string>
#include <vector>

namespace pantocat
{
/**
 * contact_force.png, dropper_forces.png and pantograph.png (Figs. 6 and 7)
 * from time_series.csv, whose header is @p columns: each plot draws the named
 * columns that exist (found by name, never by position); a plot with no such
 * column is not drawn. Writes time_series.gp and returns the PNG files that
 * gnuplot actually wrote (none if it is missing or fails).
 */
std::vector<std::string> plot_time_series(const std::string& directory,
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

/// True if gnuplot is on the PATH (looked up without a shell: find_program()).
bool gnuplot_available();

/**
 * Runs @p script (a file name in @p directory) with gnuplot inside @p
 * directory, without a shell (run_program()): the directory's name may hold
 * any character. Removes the @p outputs first and returns those gnuplot then
 * wrote (non-empty files); none if it is not installed or fails.
 */
std::vector<std::string> run_gnuplot(const std::string& directory,
                                     const std::string& script,
                                     const std::vector<std::string>& outputs);

/**
 * @p text as a single-quoted gnuplot string: quotes doubled, control
 * characters (a newline would end the command) replaced by spaces.
 */
std::string gnuplot_string(const std::string& text);
} // namespace pantocat
