#pragma once

#include <pantocat/simulation/assessment.h>
#include <pantocat/simulation/case_runner.h>
#include <pantocat/simulation/contact_statistics.h>
#include <pantocat/simulation/energy_range.h>
#include <pantocat/simulation/event_log.h>
#include <pantocat/simulation/line_windows.h>
#include <pantocat/simulation/moving_load_comparison.h>
#include <pantocat/simulation/run_statistics.h>

#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace pantocat
{
/// What a completed dynamic run leaves for summary.json and the screen.
struct RunRecord
{
  const CaseRunner& runner;
  const CaseRunner::Result& result;
  const RunStatistics& statistics;
  const EventLog& events;
  const FirstTimePoint& first_point;
  /// Per pantograph (in layout order): its contact statistics, nullptr without contact.
  std::vector<const ContactStatistics*> contacts;
  const EnergyRange* energy = nullptr;          ///< if Output/Energy
  const MovingLoadComparison* series = nullptr; ///< if a classical moving load
  /// Statistics/Episode resolution [s]: open intervals merged into episodes.
  double episode_resolution = 0.;
  /// Per pantograph (in layout order): its window's assessment; no criteria
  /// without a contact, without a window or with Assessment/Enabled = false.
  std::vector<Assessment> assessments = {};
  /// The entries the case file and the command line set ("Subsection/Name" -> value).
  std::map<std::string, std::string> inputs = {};
  /// The line's overlaps and contact wires (nullptr or empty for a single section).
  const LineWindows* line = nullptr;
  /// Pantograph 1's contact statistics (the first in contact), or nullptr.
  const ContactStatistics* first_contact() const;
  /// x_p(t) [m] of pantograph @p k (in layout order).
  double position_at(unsigned int k, double t) const;
};

/**
 * summary.json of a completed run: the case, the scene, per pantograph its
 * contact-force statistics, loss intervals and events ("pantographs"), and
 * pantograph 1's figures also at the top level (the names of version 1),
 * the constraints' events, the integrator's counters, the guards. Written
 * atomically (write_file_atomically()): complete or not at all.
 */
void write_run_summary(const std::string& file, const RunRecord& record);

/**
 * The evaluation window of one pantograph that a failed run had passed
 * (ContactStatistics::passed_window()): its figures, the dropper slack while
 * the pantograph was in it and its assessment.
 */
struct PassedWindow
{
  std::string pantograph;
  ContactForceStatistics statistics;
  DropperSlackEvents slack_in_window;
  Assessment assessment;
};

/**
 * summary.json of a run that did not complete: "failed", the @p phase it was
 * in (setup, time loop, output, ...) and the @p reason; with @p passed the
 * windows the run had passed before it failed, under "passed_windows" (per
 * window: pantograph, statistics and assessment as in a completed summary).
 * Written atomically, as write_run_summary().
 */
void write_failed_summary(const std::string& file, const std::string& phase,
                          const std::string& reason,
                          const std::vector<PassedWindow>& passed = {});

/// The effects the scene assembles, those it leaves out, and the problem size.
void print_scene(std::ostream& out, const CaseRunner& runner);

/**
 * The case in a few lines (the screen at normal verbosity): spans and length,
 * droppers, steady arms and stitch wires, each pantograph with its model,
 * contact and speed in km/h, the size of the system; then the start and
 * lambda_p(0) of each contact against its pantograph's static force.
 */
void print_case_summary(std::ostream& out, const CaseRunner& runner);

/// The run's figures on screen: contact forces per pantograph, slack and loss intervals.
void print_run_report(std::ostream& out, const RunRecord& record, bool detailed);
} // namespace pantocat
