#pragma once

#include <pantocat/simulation/time_point.h>

#include <fstream>
#include <string>
#include <vector>

namespace pantocat
{
/**
 * time_series.csv: a header row, then one row per output step with t, x_p,
 * lambda_p, lambda_d1..n, the pantograph coordinates, the gaps of contact and
 * droppers, the active flags and the constraint residuals on position and
 * velocity level. Each row is flushed: a killed run keeps its data up to the
 * last output step. The file is opened (and an earlier one replaced) by
 * start().
 */
class TimeSeriesWriter : public SimulationObserver
{
public:
  /// The columns of time_series.csv for @p layout, in order (plots find them by name).
  static std::vector<std::string> column_names(const SimulationLayout& layout);

  TimeSeriesWriter(const std::string& file, unsigned int every_n_points);
  void start(const SimulationLayout& layout) override;
  void observe(const TimePoint& point) override;
  void finish() override;
  /// The number of points seen and the length of the file.
  void save(CheckpointOut& archive) const override;
  /// Cuts the file to its length at the checkpoint (rows written after it by
  /// the stopped run go) and appends from there.
  void resume(const SimulationLayout& layout, CheckpointIn& archive) override;

private:
  std::string file_name;
  mutable std::ofstream out; ///< opened by start() or resume()
  SimulationLayout layout;
  unsigned int every;
  unsigned long seen = 0;
};
} // namespace pantocat
