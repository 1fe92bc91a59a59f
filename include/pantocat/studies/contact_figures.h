#pragma once

#include <pantocat/simulation/case_runner.h>
#include <pantocat/simulation/contact_statistics.h>
#include <pantocat/simulation/event_log.h>
#include <pantocat/simulation/statistics_parameters.h>

#include <limits>
#include <string>
#include <vector>

namespace pantocat
{
/// A switch of a unilateral constraint in a study run.
struct StudyEvent
{
  double t = 0.;               ///< [s]: located (IDA) or the first time point after it
  unsigned int constraint = 0; ///< index in the system's constraints
  bool closes = false;         ///< the contact returns, a dropper re-tensions
};

/**
 * What Study/Quantities = contact statistics measures in one run: pantograph
 * 1's contact figures in the evaluation window (subsection Statistics; those
 * of summary.json's pantographs[0].statistics), the smallest force of any
 * unilateral constraint and the switch events.
 */
struct ContactFigures
{
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double loss_percent = nan; ///< raw contact loss in the window [%] (lambda_p <= 0)
  /// Low-passed max, min, std in the window [N]; NaN without Statistics/Low-pass cut-off.
  double filtered_max = nan, filtered_min = nan, filtered_std = nan;
  /// The smallest lambda of any unilateral constraint (contacts, droppers) at
  /// any time point of the run [N]; NaN if there is none.
  double min_unilateral_force = nan;
  std::string min_unilateral_constraint; ///< its name
  double min_unilateral_time = nan;      ///< when [s]
  unsigned int contact = 0;              ///< pantograph 1's contact constraint
  /// The switches, in time order, that open and close the episodes at least
  /// Statistics/Episode resolution long (episode_events()).
  std::vector<StudyEvent> events;
  /// The episodes shorter than the resolution (all constraints): how many,
  /// and their summed length [s]; counted, not matched event by event.
  unsigned long short_episodes = 0;
  double short_episode_time = 0.;

  /// The events of pantograph 1's contact (loss and return).
  unsigned long contact_events() const;

  /// Appends the figures to @p buffer; unpack() restores them exactly.
  void pack(std::vector<char>& buffer) const;
  static ContactFigures unpack(const std::vector<char>& buffer, std::size_t& position);
};

/// The switches of a run's episodes (episode_events()).
struct EpisodeEvents
{
  std::vector<StudyEvent> events;   ///< opening and closing of each resolved episode
  unsigned long short_episodes = 0; ///< episodes shorter than the resolution
  double short_episode_time = 0.;   ///< their summed length [s]
};

/**
 * The switches of @p events (in time order) that open and close the
 * episodes of each constraint at the resolution @p resolution [s], by the
 * rule of summary.json's episodes (switch_episodes(): open intervals whose
 * reclosures are shorter than @p resolution merge; a constraint open at the
 * start or the end of the run has an interval without that end). An episode
 * at least @p resolution long keeps its first opening and its last closing;
 * a shorter one is counted in short_episodes instead. Where isolated
 * sub-millisecond separations differ between runs (a head that leaves a wire
 * just stopped by a dropper under it, for 0.1 ms, at one step and not at
 * another), the episodes that a 20 Hz evaluation sees still match one to one.
 */
EpisodeEvents episode_events(const std::vector<StudyEvent>& events, double resolution);

/**
 * Observers that measure the ContactFigures of a run: a ContactStatistics for
 * pantograph 1 (the figures of summary.json), an EventLog and the smallest
 * force of the unilateral constraints. Add observers() to the run, then call
 * figures() with the integrator's statistics (events it located replace the
 * step-resolved ones, as in summary.json).
 */
class ContactFiguresRecorder
{
public:
  ContactFiguresRecorder(const CaseRunner& runner,
                         const StatisticsParameters& statistics);

  std::vector<SimulationObserver*> observers();
  ContactFigures figures(const IntegratorStatistics& integrator) const;

private:
  /// The smallest multiplier over the unilateral constraints and the time points.
  class UnilateralMinimum : public SimulationObserver
  {
  public:
    explicit UnilateralMinimum(const SemiDiscreteSystem& system);
    void start(const SimulationLayout& layout) override;
    void observe(const TimePoint& point) override;

    double force = std::numeric_limits<double>::quiet_NaN();
    std::string constraint;
    double time = std::numeric_limits<double>::quiet_NaN();

  private:
    std::vector<unsigned int> unilateral;
    std::vector<std::string> names;
  };

  const SimulationLayout& layout;
  double episode_resolution;
  ContactStatistics contact;
  EventLog log;
  UnilateralMinimum minimum;
};
} // namespace pantocat
