#include <pantocat/io/progress_meter.h>

#include <unistd.h>

#include <cstdio>

namespace pantocat
{
ProgressMeter::ProgressMeter(std::ostream& out, const double end_time, const double delay,
                             const double updates_per_second)
    : out(out), end_time(end_time), delay(delay), period(1. / updates_per_second)
{
}

void ProgressMeter::start(const SimulationLayout&)
{
  started = last_update = Clock::now();
  points = 0;
}

void ProgressMeter::observe(const TimePoint& point)
{
  ++points;
  const auto now = Clock::now();
  const double elapsed = std::chrono::duration<double>(now - started).count();
  if (elapsed < delay ||
      std::chrono::duration<double>(now - last_update).count() < period)
    return;
  last_update = now;
  const double done = end_time > 0. ? point.t / end_time : 1.;
  const double rate = points / elapsed;
  const double left = done > 0. ? elapsed * (1. - done) / done : 0.;
  char line[160];
  std::snprintf(line, sizeof line,
                "\r  %5.1f %%  t = %.4f s of %.4f s  %.0f steps/s  %.0f s left  ",
                100. * done, point.t, end_time, rate, left);
  out << line << std::flush;
  line_shown = true;
}

void ProgressMeter::finish()
{
  if (line_shown)
    out << "\r\033[K" << std::flush; // back to the line start, erase the line
  line_shown = false;
}

bool stderr_is_terminal()
{
  return isatty(STDERR_FILENO) == 1;
}
} // namespace pantocat
