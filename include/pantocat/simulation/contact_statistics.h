#pragma once

#include <pantocat/lac/sparse_row.h>
#include <pantocat/simulation/statistics_parameters.h>
#include <pantocat/simulation/time_point.h>
#include <pantocat/space/catenary_discretisation.h>
#include <pantocat/system/semi_discrete_system.h>

#include <optional>
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
 * The figures of one contact-force series in the evaluation window, as the
 * railway field reports them (EN 50318, EN 50367): mean F_m, population
 * standard deviation sigma, F_m +/- 3 sigma, the actual maximum and minimum
 * [N], and the share of time with force <= 0. NaN without a time point.
 */
struct ForceFigures
{
  double mean = 0.;
  double std = 0.; ///< population standard deviation over the window's time points
  double max = 0., min = 0.;
  double mean_plus_3std = 0., mean_minus_3std = 0.;
  /// 100 x (time points with force <= 0) / n: contact loss, resolution one step.
  double contact_loss_percent = 0.;
  unsigned long n_points = 0;
};

/**
 * The figures of @p force at the time points @p points (indices into it);
 * NaN figures if @p points is empty. The variance in two passes (no
 * cancellation).
 */
ForceFigures force_figures(const std::vector<double>& force,
                           const std::vector<std::size_t>& points);

/// The largest rise of the contact wire at one steady arm.
struct SteadyArmUplift
{
  double x = 0.;         ///< the steady arm's position [m]
  double max_uplift = 0; ///< max over the run of w_w(x, t) - w_w(x, 0) [m]
};

/**
 * Contact-force statistics of one pantograph in its evaluation window, raw
 * and (with a cut-off) after the zero-phase low pass of the whole run, and
 * the uplift of the contact wire at the steady arms in the window.
 */
struct ContactForceStatistics
{
  EvaluationWindow window;                ///< as asked (in metres)
  double first_position = 0.;             ///< x_p [m] of the first point used
  double last_position = 0.;              ///< x_p [m] of the last point used
  double first_time = 0., last_time = 0.; ///< t [s] of the first and last point used
  double filter_cutoff_hz = 0.;           ///< 0: unfiltered
  unsigned int filter_order = 0;          ///< order of the Butterworth low pass
  ForceFigures raw;                       ///< lambda_p as computed
  std::optional<ForceFigures>
      filtered; ///< after the low pass (a cut-off set, > 2 points)
  std::vector<SteadyArmUplift> steady_arms; ///< those in the window, ends included
  /// Maximum uplift w_w(x_d, t) - w_w(x_d, 0) over the whole run per dropper [m].
  std::vector<double> max_uplift_at_droppers;

  /// The largest uplift over the steady arms in the window; none without one.
  std::optional<double> max_steady_arm_uplift() const;
};

/**
 * The statistics of @p series in @p window: the raw figures, and when
 * @p parameters set a cut-off, the figures of lambda_p filtered over the
 * whole run (sample rate from the time points) taken in the same window. A
 * window that holds no time point (narrower than one step) gives n_points =
 * 0 and NaN figures (null in summary.json). @p filtered, if given, receives
 * the filtered force of every time point (lambda_p itself without a cut-off).
 */
ContactForceStatistics evaluate_contact_force(const ContactForceSeries& series,
                                              const StatisticsParameters& parameters,
                                              const EvaluationWindow& window,
                                              std::vector<double>* filtered = nullptr);

/**
 * The points of the contact wires at which a run records the uplift, as rows
 * w = row . q in the numbering of the system: every dropper, and the steady
 * arms with their positions along the line.
 */
struct UpliftPoints
{
  std::vector<SparseRow> droppers;
  std::vector<double> steady_arm_positions;
  std::vector<SparseRow> steady_arms;
};

/**
 * Observer that records the contact-force series of one pantograph's contact
 * (one observer per contact) and the contact-wire displacement w_w(x, t) at
 * every dropper and at every steady arm inside the evaluation window (a
 * sparse row each), and evaluates the statistics at the end of the run.
 */
class ContactStatistics : public SimulationObserver
{
public:
  /**
   * For pantograph @p pantograph (its index in SimulationLayout::pantographs);
   * @p steady_arms: the positions [m] of the scene's steady arms (none if it
   * has none: SteadyArms::positions()).
   */
  ContactStatistics(const StatisticsParameters& parameters,
                    const CatenaryDiscretisation& discretisation,
                    const SemiDiscreteSystem& system,
                    const std::vector<double>& steady_arms = {},
                    unsigned int pantograph = 0);
  /// Every contact wire of the pantograph: its force is the sum over them.
  static constexpr unsigned int all_wires = static_cast<unsigned int>(-1);
  /**
   * On a line: the window from @p supports (the supports along the line of
   * the section that Statistics/Window section names), the uplift at
   * @p points, and the force of pantograph @p pantograph on contact wire
   * @p wire (its index among the pantograph's wire contacts) or on all.
   */
  ContactStatistics(const StatisticsParameters& parameters,
                    const std::vector<double>& supports, const UpliftPoints& points,
                    unsigned int pantograph, unsigned int wire = all_wires);

  void start(const SimulationLayout& layout) override;
  void observe(const TimePoint&) override {}
  void observe_state(const TimePoint& point, const DynamicState& state) override;
  void finish() override;
  void save(CheckpointOut& archive) const override;
  void resume(const SimulationLayout& layout, CheckpointIn& archive) override;

  const ContactForceStatistics& result() const { return statistics; }
  /**
   * For a run that stops early (a guard): the statistics of the window if
   * the pantograph left it at least passed_window_margin seconds before the
   * last time point recorded, evaluated on the series up to that margin only
   * (so that neither the low pass nor the uplift sees the steps that failed),
   * with the uplift at the droppers and steady arms as it was then; nothing
   * if the window was not passed (or is the whole run).
   */
  std::optional<ContactForceStatistics> passed_window() const;
  /// [s] of series kept after the window for passed_window(): five time
  /// constants of a 20 Hz low pass and more.
  static constexpr double passed_window_margin = 0.1;
  const ContactForceSeries& series() const { return recorded; }
  /// lambda_p after the low pass at every time point (= lambda_p if unfiltered).
  const std::vector<double>& filtered_force() const { return filtered; }

private:
  /// Takes the snapshot of passed_window() once the window lies the margin behind.
  void remember_passed_window();

  StatisticsParameters parameters;
  EvaluationWindow window;
  unsigned int pantograph = 0;
  unsigned int wire = all_wires;
  /// The pantograph's layout, with the contacts whose force is recorded.
  PantographLayout contact;
  /// w_w = row . q at the droppers, then at the steady arms in the window.
  std::vector<SparseRow> wire_rows;
  unsigned int n_droppers = 0;     ///< the first n_droppers of wire_rows
  std::vector<double> steady_arms; ///< x [m] of the steady arms in the window
  std::vector<double> initial_height, max_uplift; ///< per row of wire_rows
  ContactForceSeries recorded;
  /// passed_window(): the points recorded and the uplift when the window
  /// lay passed_window_margin behind (empty before).
  std::size_t passed_points = 0;
  std::vector<double> passed_uplift;
  double left_window_at = -1.; ///< [s] the first time point past the window (-1: not yet)
  ContactForceStatistics statistics;
  std::vector<double> filtered;
};
} // namespace pantocat
