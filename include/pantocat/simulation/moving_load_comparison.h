#pragma once

#include <pantocat/analysis/moving_load_series.h>
#include <pantocat/simulation/case.h>
#include <pantocat/simulation/time_point.h>

#include <vector>

namespace pantocat
{
/**
 * Compares the contact wire at the probe positions (Output/Probe positions)
 * with the series solution of the moving load (MovingLoadSeries) at every
 * reported time point: max |w - w_series| and max |w_series| per probe.
 * Attached for the scenes where that series is the exact solution of the
 * continuous problem (SceneParameters::is_classical_moving_load()).
 */
class MovingLoadComparison : public SimulationObserver
{
public:
  explicit MovingLoadComparison(MovingLoadSeries series);

  void start(const SimulationLayout& layout) override;
  void observe(const TimePoint& point) override;
  void save(CheckpointOut& archive) const override;
  void resume(const SimulationLayout& layout, CheckpointIn& archive) override;

  struct Probe
  {
    double x = 0.;
    double max_error = 0.;     ///< max_t |w - w_series| [m]
    double max_reference = 0.; ///< max_t |w_series| [m]
    double relative() const { return max_error / max_reference; }
  };
  const std::vector<Probe>& probes() const { return result; }

private:
  MovingLoadSeries series;
  std::vector<Probe> result;
};

/// The series solution of a classical moving-load case
/// (SceneParameters::is_classical_moving_load()).
MovingLoadSeries moving_load_series(const Case& c);
} // namespace pantocat
