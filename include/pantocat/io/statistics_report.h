#pragma once

#include <pantocat/io/json_writer.h>
#include <pantocat/simulation/assessment.h>
#include <pantocat/simulation/contact_statistics.h>
#include <pantocat/simulation/line_windows.h>
#include <pantocat/simulation/run_statistics.h>

#include <ostream>
#include <string>
#include <vector>

namespace pantocat
{
/**
 * The "statistics" object of summary.json (doc/output.md): "window" (x
 * [x0, x1] m, spans [first, last] or null, n_points), "raw" and "filtered"
 * (null without a cut-off; else with cutoff_hz and order) each with mean,
 * std, max, min, mean_plus_3std, mean_minus_3std [N] and
 * contact_loss_percent, max_steady_arm_uplift_m (null without a steady arm in
 * the window), "steady_arms" ([{x, max_uplift_m}]), max_uplift_at_droppers
 * [m], and @p slack_in_window as dropper_slack_events_in_window.
 */
void write_statistics(JsonWriter& json, const ContactForceStatistics& statistics,
                      const DropperSlackEvents& slack_in_window);

/**
 * "line_windows" of summary.json on a line of several sections: per
 * evaluation of @p line its pantograph, window ("window", "overlap k"),
 * contact wire ("all wires", "section k") and "statistics" as
 * write_statistics() writes them.
 */
void write_line_windows(JsonWriter& json, const LineWindows& line,
                        const SimulationLayout& layout);
/**
 * The line's evaluations on screen, one line each: the window's x, the raw
 * and low-passed F_m, sigma, F_max and F_min; with @p detailed every contact
 * wire, else the force on all wires only.
 */
void print_line_windows(std::ostream& out, const LineWindows& line,
                        const SimulationLayout& layout, bool detailed);

/// {"total": n, "per_dropper": [n_1, ...]} under @p key.
void write_slack_events(JsonWriter& json, const std::string& key,
                        const DropperSlackEvents& events);

/// A pantograph's columns in contact_force.csv.
struct ContactForceColumns
{
  const ContactStatistics* statistics;
  std::string suffix; ///< PantographLayout::column_suffix: "" with one pantograph
};

/// The header of contact_force.csv for @p pantographs (write_contact_force()).
std::vector<std::string>
contact_force_column_names(const std::vector<ContactForceColumns>& pantographs);

/**
 * contact_force.csv: t, then per pantograph in contact x_p, lambda_p and
 * lambda_p_filtered (after the low pass; equal to lambda_p without one), each
 * with the pantograph's column suffix ("" with one, "[k]" with several), at
 * every time point of the run; each number as printf's "%.10g" writes it
 * (write_csv_number(), as in time_series.csv).
 */
void write_contact_force(const std::string& file,
                         const std::vector<ContactForceColumns>& pantographs);

/**
 * The figures as a few lines of text (the end of a run's screen output): the
 * window in metres and spans, raw and filtered figures side by side, the
 * uplift at the steady arms and at the droppers, and @p slack_in_window.
 */
void print_statistics(std::ostream& out, const ContactForceStatistics& statistics,
                      const DropperSlackEvents& slack_in_window);

/**
 * The "assessment" object of a pantograph in summary.json: speed_kmh, basis
 * ("20 Hz" or "raw"), passed, and "criteria": [{name, value, limit,
 * relation ("<=" or ">"), unit, rule, passed}]; null without criteria.
 */
void write_assessment(JsonWriter& json, const Assessment& assessment);

/// One pantograph's column of print_statistics_side_by_side().
struct PantographFigures
{
  std::string name;
  const ContactForceStatistics* statistics;
  DropperSlackEvents slack_in_window;
  const Assessment* assessment; ///< null or without criteria: not assessed
};

/**
 * The window figures of several pantographs in one table, a column each (the
 * low-passed figures where there are, the contact loss of the raw force, the
 * uplift at the steady arms and the dropper slack events in the window), then
 * one line per pantograph with its verdict and the criteria it fails: the
 * screen of a run with several pantographs (each pantograph's full block:
 * Output/Verbosity = detailed).
 */
void print_statistics_side_by_side(std::ostream& out,
                                   const std::vector<PantographFigures>& columns);

/// The assessment as a few lines of text: one per criterion, value, limit, pass or fail.
void print_assessment(std::ostream& out, const Assessment& assessment);

/// "total 3 (dropper 41: 1, dropper 42: 2)", "total 69 on 23 droppers (most:
/// dropper 37: 8)" when more than five droppers have events, or "none".
std::string describe_slack_events(const DropperSlackEvents& events);
} // namespace pantocat
