#pragma once

#include <pantocat/simulation/assessment.h>

#include <ostream>
#include <string>
#include <vector>

namespace pantocat
{
enum class SweepKind;

/**
 * A sweep's CSV read back (the figures at their printed digits, so that a
 * resumed sweep reports the same distribution as an uninterrupted one).
 */
struct SweepTable
{
  std::vector<std::string> key_columns;
  struct Row
  {
    std::vector<std::string> key;
    unsigned int pantograph = 1;
    std::vector<double> values; ///< sweep_statistic_columns(); NaN where empty
    std::string status, reason;
  };
  std::vector<Row> rows;

  /// The pantograph numbers in the table, increasing.
  std::vector<unsigned int> pantographs() const;
  /// Column index of statistic @p name in Row::values.
  static unsigned int statistic(const std::string& name);
};

/// Parses a sweep CSV (header and rows of sweep_rows()) with @p n_keys key columns.
SweepTable read_sweep_table(const std::string& csv, unsigned int n_keys);

/**
 * The distribution of every statistic over the completed samples, per
 * pantograph: statistic, pantograph, n, mean, std (population), min, p5,
 * p50, p95, max (percentiles linear between order statistics).
 */
std::string monte_carlo_distribution_csv(const SweepTable& table);

/// The distribution of the main figures and the samples that lost contact or failed.
void print_monte_carlo_summary(std::ostream& out, const SweepTable& table);

/**
 * The plots of a sweep written by gnuplot from <name>.csv in @p directory
 * (scripts <name>*.gp beside them): a speed sweep's statistics against
 * speed (mean, the mean +/- 3 sigma band, max and min, contact loss on the
 * second axis; sigma below it, with 0.7 @p wave_speed marked); a parameter
 * sweep's one plot per statistic against the first entry (one curve per
 * value of the second); a Monte Carlo study's histograms. One file per
 * pantograph when there are several; the speed plot with the force limits
 * of @p criteria (target F_m against speed, F_max, sigma <= ratio F_m) if
 * given; a parameter sweep's x axis with @p key_unit. Each PNG also as an
 * SVG copy (for the sweep's report). Returns the files written.
 */
std::vector<std::string> plot_sweep(const std::string& directory, const std::string& name,
                                    SweepKind kind, const SweepTable& table,
                                    double wave_speed,
                                    const AssessmentCriteria* criteria = nullptr,
                                    const std::string& key_unit = "");
} // namespace pantocat
