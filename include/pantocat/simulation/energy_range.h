#pragma once

#include <pantocat/simulation/time_point.h>

namespace pantocat
{
/**
 * The range of the energy E(t) = T + V - f(t)^T q over the reported time
 * points (Output/Energy): a conservation check users can see (a reversible
 * method on an undamped scene keeps it constant to O((omega dt)^2)).
 */
class EnergyRange : public SimulationObserver
{
public:
  void observe(const TimePoint& point) override;
  void save(CheckpointOut& archive) const override;
  void resume(const SimulationLayout& layout, CheckpointIn& archive) override;

  /// max |E(t) - E(0)| / |E(0)|.
  double relative_variation() const;

  unsigned long count = 0;
  double initial = 0., min = 0., max = 0., final = 0.;
};

/**
 * The first reported time point: for the consistency check of the initial
 * state (the first step returns lambda_p = lambda_p(0), Sec. 2.2), which a
 * method with lagging multipliers reports only after its first step.
 */
class FirstTimePoint : public SimulationObserver
{
public:
  void observe(const TimePoint& point) override;
  void save(CheckpointOut& archive) const override;
  void resume(const SimulationLayout& layout, CheckpointIn& archive) override;

  bool seen = false;
  double t = 0.;
  std::vector<double> lambda; ///< per constraint [N]
};
} // namespace pantocat
