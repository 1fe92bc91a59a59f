#pragma once

#include <pantocat/simulation/assessment.h>
#include <pantocat/studies/sweep_plots.h>

#include <string>
#include <vector>

namespace pantocat
{
enum class SweepKind;

/// What a sweep's report shows besides its table.
struct SweepReportInput
{
  std::string name;                   ///< the sweep's file base name
  SweepKind kind;                     ///< speed sweep, parameter sweep or Monte Carlo
  const AssessmentCriteria* criteria; ///< null or disabled: no assessment
  double speed = 0.;            ///< [m/s] the base case's speed (all but speed sweeps)
  double filter_cutoff_hz = 0.; ///< of the low-passed figures (0: raw only)
  std::vector<std::string> svg_files; ///< pictures in the directory, in order
};

/**
 * The assessment of one row of a sweep's table at @p speed [m/s]: assess()
 * on the row's figures (the low-passed ones when the row has them, as for a
 * single run). No criteria for a row without figures.
 */
Assessment assess_sweep_row(const SweepTable::Row& row, double speed,
                            const AssessmentCriteria& criteria, double filter_cutoff_hz);

/**
 * <name>_report.html in @p directory: one self-contained page with the
 * sweep's pictures inline (statistics against speed with the limits), and
 * per pantograph a table of every run: its key, status, window figures and
 * the verdict of the assessment with the criteria it fails. Written atomically.
 */
void write_sweep_report(const std::string& directory, const SweepTable& table,
                        const SweepReportInput& input);
} // namespace pantocat
