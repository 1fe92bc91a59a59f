#pragma once

#include <pantocat/simulation/assessment.h>
#include <pantocat/simulation/contact_statistics.h>

#include <ostream>
#include <string>
#include <vector>

namespace pantocat
{
/// A gnuplot script written into a directory and the files it draws.
struct PlotScript
{
  std::string script;               ///< file name in the directory
  std::vector<std::string> outputs; ///< the PNG files it draws (none: nothing to draw)
};

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

/// Writes time_series.gp as plot_time_series() does and returns it, not run.
PlotScript time_series_script(const std::string& directory,
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

/// Writes contact_force_statistics.gp and returns it, not run.
PlotScript contact_force_statistics_script(const std::string& directory,
                                           const ContactForceStatistics& statistics,
                                           const std::string& title);

/// One pantograph's plot of contact_force_over_x.gp.
struct ForceOverXPlot
{
  std::string png;       ///< the file to draw (contact_force_over_x_file())
  std::string name;      ///< the pantograph's name, for the title
  std::string suffix;    ///< its column suffix in contact_force.csv
  double x_begin, x_end; ///< x_p [m] of its first and last time point
  const ContactForceStatistics* statistics;
  /// Its window's assessment: the force limits are drawn over the window (may be null).
  const Assessment* assessment = nullptr;
};

/// "contact_force_over_x.png", or with @p several pantographs
/// "contact_force_over_x_pantograph_2.png" for pantograph @p name "pantograph 2".
std::string contact_force_over_x_file(const std::string& name, bool several);

/**
 * contact_force_over_x.png (one per pantograph, contact_force_over_x_file()):
 * lambda_p over x_p from contact_force.csv, whose header is @p columns (found
 * by name with the pantograph's suffix), raw and (with a cut-off) low-passed,
 * dashed vertical lines at the supports @p supports with the spans numbered,
 * the evaluation window shaded, and across it the window's F_m and the force
 * limits of the plot's assessment; each also as an SVG copy (svg_file_of()).
 * Script: contact_force_over_x.gp. Returns the files gnuplot wrote.
 */
std::vector<std::string>
plot_contact_force_over_x(const std::string& directory,
                          const std::vector<std::string>& columns,
                          const std::vector<ForceOverXPlot>& plots,
                          const std::vector<double>& supports, const std::string& title);

/// Writes contact_force_over_x.gp and returns it, not run (@p plots not empty).
PlotScript contact_force_over_x_script(const std::string& directory,
                                       const std::vector<std::string>& columns,
                                       const std::vector<ForceOverXPlot>& plots,
                                       const std::vector<double>& supports,
                                       const std::string& title);

/// True if gnuplot is on the PATH (looked up without a shell: find_program()).
bool gnuplot_available();

/**
 * Runs @p script (a file name in @p directory) with gnuplot inside @p
 * directory, without a shell (run_program()): the directory's name may hold
 * any character. Removes the @p outputs first; gnuplot writes them into a
 * directory made for this call (PrivateDirectory, passed to the script as
 * gnuplot_output_directory), from where those written are renamed into
 * @p directory: no link planted at a plot's name is followed. Returns the
 * outputs written (non-empty files); none if gnuplot is not installed or fails.
 */
std::vector<std::string> run_gnuplot(const std::string& directory,
                                     const std::string& script,
                                     const std::vector<std::string>& outputs);

/**
 * Runs the @p scripts in one gnuplot process, as run_gnuplot() runs one
 * (a script that fails costs only its own outputs: the scripts with outputs
 * missing then run again one by one). Returns the outputs written.
 */
std::vector<std::string> run_gnuplot(const std::string& directory,
                                     const std::vector<PlotScript>& scripts);

/**
 * @p text as a single-quoted gnuplot string holding only characters that
 * gnuplot takes literally there: letters, digits, bytes above 0x7f, space
 * and + - * / = _ . , : ; ( ) [ ] < > % # ! ? & | ~ ^ { } (the terminals are
 * noenhanced). Every other character becomes '_' (a quote, a back quote,
 * '@', '$', '\\', '"'), a control character a space (a newline would end
 * the command). The one way user text (titles, labels, column names, values)
 * enters a script.
 */
std::string gnuplot_string(const std::string& text);

/// The gnuplot variable that holds the directory the plots are written to.
constexpr const char* gnuplot_output_directory = "output_directory";

/**
 * The first lines of a script: "# Redraw with: gnuplot <script> ...",
 * @p comment (whole lines), and the default of gnuplot_output_directory (the
 * script's own directory when it is run by hand).
 */
void begin_gnuplot_script(std::ostream& gp, const std::string& script,
                          const std::string& comment = "");

/// "set output output_directory.'<file>'" for the checked file name @p file.
std::string gnuplot_output(const std::string& file);

/// Script lines: dashed lines at the @p supports inside [x0, x1], the spans numbered.
void mark_supports(std::ostream& gp, const std::vector<double>& supports, double x0,
                   double x1);

/// Script lines: the evaluation window @p w, clipped to [x0, x1], shaded behind the
/// curves.
void shade_window(std::ostream& gp, const EvaluationWindow& w, double x0, double x1);

/// @p png with the extension .svg: the file of its copy for report.html.
std::string svg_file_of(const std::string& png);

/**
 * The script lines that draw the last plot again as the SVG picture
 * svg_file_of(@p png) (width @p width pixels, for report.html) and then
 * return to @p terminal (the script's PNG terminal line).
 */
std::string svg_copy(const std::string& png, unsigned int width, unsigned int height,
                     const std::string& terminal);
} // namespace pantocat
