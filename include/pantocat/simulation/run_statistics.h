#pragma once

#include <pantocat/simulation/time_point.h>

#include <limits>
#include <utility>
#include <vector>

namespace pantocat
{
/// A time interval [t0, t1] in seconds.
using Interval = std::pair<double, double>;

/// How often each dropper went slack: the number of its slack intervals.
struct DropperSlackEvents
{
  std::vector<unsigned long> per_dropper; ///< in dropper order
  unsigned long total = 0;                ///< the sum over the droppers
};

/**
 * Statistics of a run as summary.json reports them: contact-force statistics,
 * the intervals in which each dropper is slack and the contact is lost, and
 * the largest constraint residuals. An interval starts at the first time
 * point at which the constraint is inactive and ends at the first at which it
 * is active again (or at the end of the run): resolution one output step.
 */
class RunStatistics : public SimulationObserver
{
public:
  void start(const SimulationLayout& layout) override;
  void observe(const TimePoint& point) override;
  void finish() override;
  void save(CheckpointOut& archive) const override;
  void resume(const SimulationLayout& layout, CheckpointIn& archive) override;

  /// The contact force of one contact over all time points (uniform steps).
  struct ForceStatistics
  {
    double max = -std::numeric_limits<double>::infinity();
    double min = std::numeric_limits<double>::infinity();
    double mean = 0., m2 = 0.;
    unsigned long count = 0;
    /// Where the extremes were first reached: t [s] and x_p [m].
    double max_time = 0., max_position = 0., min_time = 0., min_position = 0.;

    /// Adds @p force at time @p t with the pantograph at @p x.
    void add(double force, double t = 0., double x = 0.);
    /// Population standard deviation.
    double std() const;
  };

  /**
   * Impacts of one constraint (Sec. 5.3: a closing unilateral constraint,
   * inelastic): how often it closed, the largest impulse at a closing [N s],
   * and the sum of all its impulses (with its share of the impacts of other
   * constraints while it held). The force statistics hold lambda only; an
   * impulse is a Dirac measure of the force and is counted here, never in them.
   */
  struct ImpulseStatistics
  {
    unsigned long count = 0;
    double total = 0., max = 0.;
  };
  /// Of constraint @p i.
  const ImpulseStatistics& impulses(unsigned int i) const { return impacts[i]; }
  /// Summed over the droppers.
  ImpulseStatistics dropper_impulses() const;

  /// Of pantograph @p k's contact (k in the order of SimulationLayout::pantographs).
  const ForceStatistics& contact_force(unsigned int k) const { return forces[k]; }
  /// Of the first pantograph in contact (pantograph 1 in version 1's outputs).
  const ForceStatistics& first_contact_force() const { return first_contact(); }
  double contact_force_max() const { return first_contact().max; }
  double contact_force_min() const { return first_contact().min; }
  double contact_force_mean() const { return first_contact().mean; }
  /// Population standard deviation over the time points (uniform steps).
  double contact_force_std() const { return first_contact().std(); }
  unsigned long n_points() const { return first_contact().count; }
  double max_position_residual() const { return max_pos; }
  double max_velocity_residual() const { return max_vel; }
  /// The largest number of droppers slack at the same time point.
  unsigned int max_droppers_slack_at_once() const { return max_slack; }
  /// Slack intervals of each dropper, in dropper order.
  std::vector<std::vector<Interval>> dropper_slack_intervals() const;
  /**
   * The slack intervals of each dropper that begin at a time in [@p from,
   * @p to] (by default all of the run), counted.
   */
  DropperSlackEvents
  dropper_slack_events(double from = -std::numeric_limits<double>::infinity(),
                       double to = std::numeric_limits<double>::infinity()) const;
  /// Loss intervals of the first pantograph's contact.
  std::vector<Interval> contact_loss_intervals() const;
  /// Loss intervals of pantograph @p k's contact (empty without contact).
  std::vector<Interval> contact_loss_intervals(unsigned int k) const;
  /// Inactive intervals of constraint i.
  const std::vector<Interval>& inactive_intervals(unsigned int i) const
  {
    return intervals[i];
  }

private:
  const ForceStatistics& first_contact() const;

  SimulationLayout layout;
  std::vector<ForceStatistics> forces; ///< per pantograph (unused without contact)
  double max_pos = 0., max_vel = 0.;
  double last_t = 0.;
  unsigned int max_slack = 0;
  std::vector<std::vector<Interval>> intervals;
  std::vector<double> open_since;         ///< start of the open interval, or NaN
  std::vector<ImpulseStatistics> impacts; ///< per constraint
  /// Per pantograph: the intervals in which it touches no contact wire, and
  /// the start of the open one (NaN if it touches one).
  std::vector<std::vector<Interval>> losses;
  std::vector<double> lost_since;
};
} // namespace pantocat
