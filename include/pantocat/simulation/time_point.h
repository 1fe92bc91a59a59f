#pragma once

#include <string>
#include <vector>

namespace pantocat
{
/// What the outputs know about a dynamic run: names and roles of the constraints.
struct SimulationLayout
{
  std::vector<std::string> constraint_names; ///< in system order: droppers, then contact
  std::vector<std::string> pantograph_coordinates;
  unsigned int contact_index = 0;
  std::vector<unsigned int> dropper_indices;
};

/// One reported time point of a dynamic run.
struct TimePoint
{
  double t = 0.;
  double x_p = 0.;
  std::vector<double> lambda;     ///< per constraint [N]
  std::vector<double> gap;        ///< g_i(t, q) per constraint [m]
  std::vector<bool> active;       ///< per constraint
  std::vector<double> pantograph; ///< q_MBS
  double position_residual = 0.;  ///< max |g_i| over active constraints
  double velocity_residual = 0.;  ///< max |dg_i/dt| over active constraints
};

/// Receives the time points of a run (time series, statistics, plots, ...).
class SimulationObserver
{
public:
  virtual ~SimulationObserver() = default;
  virtual void start(const SimulationLayout&) {}
  virtual void observe(const TimePoint& point) = 0;
  virtual void finish() {}
};
} // namespace pantocat
