#pragma once

#include <pantocat/simulation/time_point.h>

#include <fstream>
#include <string>

namespace pantocat
{
/**
 * time_series.csv: a header row, then one row per output step with t, x_p,
 * lambda_p, lambda_d1..n, the pantograph coordinates, the gaps of contact and
 * droppers, the active flags and the constraint residuals on position and
 * velocity level. Each row is flushed: a killed run keeps its data up to the
 * last output step.
 */
class TimeSeriesWriter : public SimulationObserver
{
public:
  TimeSeriesWriter(const std::string& file, unsigned int every_n_points);
  void start(const SimulationLayout& layout) override;
  void observe(const TimePoint& point) override;
  void finish() override;

private:
  std::string file_name;
  std::ofstream out;
  SimulationLayout layout;
  unsigned int every;
  unsigned long seen = 0;
};
} // namespace pantocat
