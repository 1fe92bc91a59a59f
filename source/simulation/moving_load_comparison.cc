#include <pantocat/base/serialization.h>
#include <pantocat/simulation/moving_load_comparison.h>

#include <algorithm>
#include <cmath>

namespace pantocat
{
MovingLoadComparison::MovingLoadComparison(MovingLoadSeries series)
    : series(std::move(series))
{
}

void MovingLoadComparison::start(const SimulationLayout& layout)
{
  result.clear();
  for (const double x : layout.probe_positions)
    result.push_back({x, 0., 0.});
}

void MovingLoadComparison::save(CheckpointOut& archive) const
{
  for (const Probe& probe : result)
    archive << probe.max_error << probe.max_reference;
}

void MovingLoadComparison::resume(const SimulationLayout& layout, CheckpointIn& archive)
{
  start(layout);
  for (Probe& probe : result)
    archive >> probe.max_error >> probe.max_reference;
}

void MovingLoadComparison::observe(const TimePoint& point)
{
  for (std::size_t j = 0; j < result.size(); ++j)
  {
    const double reference = series.displacement(result[j].x, point.t);
    result[j].max_error =
        std::max(result[j].max_error, std::abs(point.probes[j] - reference));
    result[j].max_reference = std::max(result[j].max_reference, std::abs(reference));
  }
}
} // namespace pantocat
