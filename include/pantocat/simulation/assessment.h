#pragma once

#include <pantocat/simulation/contact_statistics.h>

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace pantocat
{
/**
 * Subsection Assessment: the criteria a line is assessed by, as data. The
 * defaults are the values commonly quoted from EN 50367 and the TSI Energy
 * for AC lines (doc/evaluation.md, "Assessment"); check them against your copy
 * of the standard.
 */
struct AssessmentCriteria
{
  bool enabled = true;
  /// F_m <= a v^2 + b, v in km/h: the target mean force (AC: 0.00097, 70 N).
  double mean_force_a = 0.00097;       ///< [N h^2/km^2]
  double mean_force_b = 70.;           ///< [N]
  double max_sigma_ratio = 0.3;        ///< sigma <= ratio F_m
  double min_statistical_force = 0.;   ///< F_m - 3 sigma > this [N]
  double max_contact_force = 350.;     ///< F_max <= this [N]; 0: not assessed
  double max_steady_arm_uplift = 0.12; ///< [m]; 0: not assessed
  double max_contact_loss = 0.2;       ///< [%] of the window's time

  static void declare_parameters(dealii::ParameterHandler& prm);
  void parse_parameters(dealii::ParameterHandler& prm);
};

/// One criterion evaluated: value against limit.
struct CriterionResult
{
  std::string name;     ///< "mean_force", "sigma", ... (summary.json keys)
  std::string quantity; ///< "mean force F_m", ... (screen and report)
  std::string unit;     ///< "N", "m", "%"
  double value = 0.;
  double limit = 0.;
  bool at_most = true; ///< value <= limit; otherwise value > limit
  std::string rule;    ///< how the limit was found ("0.00097 v^2 + 70 N at 320 km/h")
  bool passed = false;
};

/// The assessment of one pantograph's window.
struct Assessment
{
  double speed_kmh = 0.;
  /// "20 Hz" (the filtered figures) or "raw" (no low pass set).
  std::string basis;
  std::vector<CriterionResult> criteria;

  bool passed() const;
};

/**
 * Evaluates @p criteria on @p statistics of a pantograph running at
 * @p speed [m/s]: the force criteria on the low-passed figures when there are
 * any (EN 50367 assesses the 0-20 Hz force), on the raw ones otherwise; the
 * contact loss on the raw force; the uplift at the steady arms in the
 * window. A window without points gives no criteria.
 */
Assessment assess(const ContactForceStatistics& statistics, double speed,
                  const AssessmentCriteria& criteria);
} // namespace pantocat
