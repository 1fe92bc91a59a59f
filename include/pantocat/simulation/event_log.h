#pragma once

#include <pantocat/simulation/time_point.h>

#include <string>
#include <vector>

namespace pantocat
{
/// A switch of a unilateral constraint (Sec. 5.3): a dropper slackens or
/// re-tensions, the contact is lost or returns.
struct ConstraintEvent
{
  double t = 0.;          ///< first reported time with the new state [s]
  std::string constraint; ///< e.g. "dropper 2", "contact"
  std::string kind; ///< dropper_slack | dropper_taut | contact_loss | contact_return
  /// The impulse [N s] of the impact of a closing event (Sec. 5.3: inelastic);
  /// 0 for a release.
  double impulse = 0.;
};

/**
 * Records every switch of the active set between consecutive time points, as
 * summary.json's "events" lists them. The fixed-step integrators switch at
 * step resolution (Sec. 5.3: "we do not determine exactly the time instant"),
 * so an event's time is the first time point with the new state; it lies
 * within one step after the true switch.
 */
class EventLog : public SimulationObserver
{
public:
  void start(const SimulationLayout& layout) override;
  void observe(const TimePoint& point) override;
  void save(CheckpointOut& archive) const override;
  void resume(const SimulationLayout& layout, CheckpointIn& archive) override;

  const std::vector<ConstraintEvent>& events() const { return list; }

private:
  SimulationLayout layout;
  std::vector<bool> previous;
  std::vector<ConstraintEvent> list;
};
} // namespace pantocat
