#include <pantocat/base/serialization.h>
#include <pantocat/simulation/energy_range.h>

#include <algorithm>
#include <cmath>

namespace pantocat
{
void EnergyRange::observe(const TimePoint& point)
{
  if (count++ == 0)
    initial = min = max = point.energy;
  min = std::min(min, point.energy);
  max = std::max(max, point.energy);
  final = point.energy;
}

void EnergyRange::save(CheckpointOut& archive) const
{
  archive << count << initial << min << max << final;
}

void EnergyRange::resume(const SimulationLayout&, CheckpointIn& archive)
{
  archive >> count >> initial >> min >> max >> final;
}

double EnergyRange::relative_variation() const
{
  return std::max(max - initial, initial - min) / std::abs(initial);
}

void FirstTimePoint::observe(const TimePoint& point)
{
  if (seen)
    return;
  seen = true;
  t = point.t;
  lambda = point.lambda;
}

void FirstTimePoint::save(CheckpointOut& archive) const
{
  archive << seen << t << lambda;
}

void FirstTimePoint::resume(const SimulationLayout&, CheckpointIn& archive)
{
  archive >> seen >> t >> lambda;
}
} // namespace pantocat
