#pragma once

#include <pantocat/base/safe_files.h>
#include <pantocat/simulation/time_point.h>

#include <optional>
#include <string>
#include <vector>

namespace pantocat
{
/**
 * time_series.csv: a header row, then one row per output step with t, x_p,
 * lambda_p, lambda_d1..n, the pantograph coordinates, the gaps of contact and
 * droppers, the active flags and the constraint residuals on position and
 * velocity level. Every @p every_n_points-th time point is written
 * (Output/Time series interval). Rows go through the stream's buffer, flushed
 * at a checkpoint and at the end. The file is opened (and an earlier one
 * replaced) by start().
 */
class TimeSeriesWriter : public SimulationObserver
{
public:
  /// The columns of time_series.csv for @p layout, in order (plots find them by name).
  static std::vector<std::string> column_names(const SimulationLayout& layout);
  /**
   * The columns @p column ("lambda_p", "gap_p", "active_p") of pantograph
   * @p p: one per contact wire it can touch, "lambda_p[1]_w2" for pantograph
   * 1 on the contact wire of section 2 of a line ("lambda_p[1]" with one).
   */
  static std::vector<std::string> contact_columns(const PantographLayout& p,
                                                  const std::string& column);

  TimeSeriesWriter(const std::string& file, unsigned int every_n_points);
  void start(const SimulationLayout& layout) override;
  void observe(const TimePoint& point) override;
  void finish() override;
  /// The number of points seen and the length of the file.
  void save(CheckpointOut& archive) const override;
  /**
   * Reads the file's length at the checkpoint. The file is cut to it (rows
   * written after it by the stopped run go) and appended to from there only
   * when the next point comes: a resume refused by a later part of the
   * checkpoint leaves the file as it was.
   */
  void resume(const SimulationLayout& layout, CheckpointIn& archive) override;

private:
  /// After resume(): cuts the file to its length at the checkpoint and opens it.
  void reopen_after_resume();
  /// Keeps @p l, its contacts' multiplier indices and a row buffer long enough.
  void take_layout(const SimulationLayout& l);

  std::optional<unsigned long> resume_length; ///< set by resume() until reopened
  std::string file_name;
  mutable std::optional<OutputFile> out; ///< opened by start() or resume()
  SimulationLayout layout;
  unsigned int every;
  unsigned long seen = 0;
  std::vector<unsigned int>
      contacts;          ///< the contacts' multiplier indices, in column order
  std::vector<char> row; ///< the row being formatted (its longest length)
};
} // namespace pantocat
