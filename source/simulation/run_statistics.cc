#include <pantocat/base/serialization.h>
#include <pantocat/simulation/run_statistics.h>

#include <algorithm>
#include <cmath>

namespace pantocat
{
void RunStatistics::start(const SimulationLayout& l)
{
  layout = l;
  intervals.assign(l.constraint_names.size(), {});
  open_since.assign(l.constraint_names.size(), std::nan(""));
}

void RunStatistics::observe(const TimePoint& p)
{
  if (layout.has_contact())
  {
    const double f = p.lambda[layout.contact_index];
    max_force = std::max(max_force, f);
    min_force = std::min(min_force, f);
    // Welford's update: no cancellation in the variance.
    ++count;
    const double delta = f - mean;
    mean += delta / count;
    m2 += delta * (f - mean);
  }
  max_pos = std::max(max_pos, p.position_residual);
  max_vel = std::max(max_vel, p.velocity_residual);
  unsigned int slack = 0;
  for (const unsigned int i : layout.dropper_indices)
    slack += p.active[i] ? 0 : 1;
  max_slack = std::max(max_slack, slack);
  for (unsigned int i = 0; i < p.active.size(); ++i)
  {
    const bool open = !std::isnan(open_since[i]);
    if (!p.active[i] && !open)
      open_since[i] = p.t;
    else if (p.active[i] && open)
    {
      intervals[i].push_back({open_since[i], p.t});
      open_since[i] = std::nan("");
    }
  }
  last_t = p.t;
}

void RunStatistics::finish()
{
  for (unsigned int i = 0; i < open_since.size(); ++i)
    if (!std::isnan(open_since[i]))
    {
      intervals[i].push_back({open_since[i], last_t});
      open_since[i] = std::nan("");
    }
}

double RunStatistics::contact_force_mean() const
{
  return mean;
}

double RunStatistics::contact_force_std() const
{
  return count > 1 ? std::sqrt(m2 / count) : 0.;
}

std::vector<std::vector<Interval>> RunStatistics::dropper_slack_intervals() const
{
  std::vector<std::vector<Interval>> result;
  for (const unsigned int i : layout.dropper_indices)
    result.push_back(intervals[i]);
  return result;
}

std::vector<Interval> RunStatistics::contact_loss_intervals() const
{
  return layout.has_contact() ? intervals[layout.contact_index] : std::vector<Interval>{};
}

void RunStatistics::save(CheckpointOut& archive) const
{
  archive << max_force << min_force << mean << m2 << count << max_pos << max_vel << last_t
          << intervals << open_since << max_slack;
}

void RunStatistics::resume(const SimulationLayout& l, CheckpointIn& archive)
{
  layout = l;
  archive >> max_force >> min_force >> mean >> m2 >> count >> max_pos >> max_vel >>
      last_t >> intervals >> open_since >> max_slack;
}
} // namespace pantocat
