#pragma once

#include <pantocat/simulation/statistics_parameters.h>
#include <pantocat/simulation/time_point.h>
#include <pantocat/space/catenary_discretisation.h>
#include <pantocat/system/semi_discrete_system.h>
#include <pantocat/system/sparse_row.h>

#include <vector>

namespace pantocat
{
/// The contact force lambda_p of a run at its time points (uniform steps).
struct ContactForceSeries
{
  std::vector<double> t, x_p, lambda_p;
  std::vector<bool> in_contact; ///< the contact constraint is active
};

/**
 * Contact-force statistics as the railway field reports them (EN 50318,
 * EN 50367): mean F_m, standard deviation sigma, F_m -/+ 3 sigma, the actual
 * maximum and minimum, and the share of time without contact; all in a
 * window of pantograph positions, optionally after a zero-phase low pass.
 */
struct ContactForceStatistics
{
  double mean = 0.;
  double std = 0.; ///< population standard deviation over the window's time points
  double mean_minus_3_sigma = 0., mean_plus_3_sigma = 0.;
  double max = 0., min = 0.;
  double percent_without_contact = 0.;       ///< 100 x share of the window's time points
  double filter_cutoff_hz = 0.;              ///< 0: unfiltered
  double window_start = 0., window_end = 0.; ///< x_p [m] of the first and last point used
  unsigned long n_points = 0;
  /// Maximum over the run of w_w(x_d, t) - w_w(x_d, 0) per dropper [m].
  std::vector<double> max_uplift_at_droppers;
};

/**
 * The statistics of @p series: filters lambda_p over the whole run (when a
 * cut-off is set; sample rate from the time points), then takes the points
 * with x_p in the window. A window that holds no time point (narrower than
 * one step) gives n_points = 0 and NaN figures (null in summary.json).
 * @p filtered, if given, receives the (filtered) force of every time point.
 */
ContactForceStatistics evaluate_contact_force(const ContactForceSeries& series,
                                              const StatisticsParameters& parameters,
                                              std::vector<double>* filtered = nullptr);

/**
 * Observer that records the contact-force series of one pantograph's contact
 * (one observer per contact) and the contact-wire
 * displacement w_w(x_d, t) at every dropper position x_d (two sparse rows
 * per time point), and evaluates the statistics at the end of the run.
 */
class ContactStatistics : public SimulationObserver
{
public:
  /// For pantograph @p pantograph (its index in SimulationLayout::pantographs).
  ContactStatistics(const StatisticsParameters& parameters,
                    const CatenaryDiscretisation& discretisation,
                    const SemiDiscreteSystem& system, unsigned int pantograph = 0);

  void start(const SimulationLayout& layout) override;
  void observe(const TimePoint&) override {}
  void observe_state(const TimePoint& point, const DynamicState& state) override;
  void finish() override;
  void save(CheckpointOut& archive) const override;
  void resume(const SimulationLayout& layout, CheckpointIn& archive) override;

  const ContactForceStatistics& result() const { return statistics; }
  const ContactForceSeries& series() const { return recorded; }
  /// lambda_p after the low pass at every time point (= lambda_p if unfiltered).
  const std::vector<double>& filtered_force() const { return filtered; }

private:
  StatisticsParameters parameters;
  unsigned int pantograph = 0;
  unsigned int contact_index = 0;
  std::vector<SparseRow> dropper_rows; ///< w_w(x_d) = row . q
  std::vector<double> initial_height, max_uplift;
  ContactForceSeries recorded;
  ContactForceStatistics statistics;
  std::vector<double> filtered;
};
} // namespace pantocat
