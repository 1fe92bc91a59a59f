#pragma once

#include <pantocat/simulation/time_point.h>

#include <chrono>
#include <ostream>

namespace pantocat
{
/**
 * A progress line for a terminal: percent done, simulated time, steps per
 * second and the time left, rewritten in place (carriage return) at most
 * @p updates_per_second times a second, starting only after @p delay seconds
 * (short runs print nothing), and cleared at the end. Whether to attach it at
 * all is the caller's decision (stderr a terminal, verbosity not quiet):
 * see progress_wanted().
 */
class ProgressMeter : public SimulationObserver
{
public:
  ProgressMeter(std::ostream& out, double end_time, double delay = 1.,
                double updates_per_second = 4.);

  void start(const SimulationLayout&) override;
  void observe(const TimePoint& point) override;
  void finish() override;
  /// Not in checkpoints (a resumed run shows its own progress; a terminal may not be).
  bool checkpointed() const override { return false; }

  /// True once a progress line has been printed (and not yet cleared).
  bool shown() const { return line_shown; }

private:
  using Clock = std::chrono::steady_clock;
  std::ostream& out;
  double end_time, delay, period;
  Clock::time_point started, last_update;
  unsigned long points = 0;
  bool line_shown = false;
};

/// True if the file descriptor 2 (stderr) is a terminal.
bool stderr_is_terminal();
} // namespace pantocat
