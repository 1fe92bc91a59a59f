#include <pantocat/base/serialization.h>
#include <pantocat/simulation/moving_load_comparison.h>

#include <optional>

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

MovingLoadSeries moving_load_series(const Case& c)
{
  WireParameters wire = c.catenary.contact_wire;
  if (!c.scene.contact_wire_tension)
    wire.tension = 0.;
  if (!c.scene.contact_wire_bending)
    wire.bending_stiffness = 0.;
  std::optional<SmoothedDelta> delta;
  if (c.discretisation.load_shape == LoadShape::smoothed_delta)
    delta.emplace(c.discretisation.load_half_width);
  const PantographCase& load = c.scene.pantographs.front();
  return MovingLoadSeries(wire, c.catenary.length(), load.moving_force,
                          load.parameters.motion(), delta);
}
} // namespace pantocat
