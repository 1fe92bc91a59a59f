#include <pantocat/base/serialization.h>
#include <pantocat/simulation/run_statistics.h>

#include <algorithm>
#include <cmath>

namespace pantocat
{
void RunStatistics::ForceStatistics::add(const double f, const double t, const double x)
{
  if (f > max)
    max = f, max_time = t, max_position = x;
  if (f < min)
    min = f, min_time = t, min_position = x;
  // Welford's update: no cancellation in the variance.
  ++count;
  const double delta = f - mean;
  mean += delta / count;
  m2 += delta * (f - mean);
}

double RunStatistics::ForceStatistics::std() const
{
  return count > 1 ? std::sqrt(m2 / count) : 0.;
}

const RunStatistics::ForceStatistics& RunStatistics::first_contact() const
{
  static const ForceStatistics none;
  for (unsigned int k = 0; k < layout.pantographs.size(); ++k)
    if (layout.pantographs[k].has_contact())
      return forces[k];
  return none;
}

void RunStatistics::start(const SimulationLayout& l)
{
  layout = l;
  forces.assign(l.pantographs.size(), {});
  intervals.assign(l.constraint_names.size(), {});
  losses.assign(l.pantographs.size(), {});
  lost_since.assign(l.pantographs.size(), std::nan(""));
  open_since.assign(l.constraint_names.size(), std::nan(""));
  impacts.assign(l.constraint_names.size(), {});
}

RunStatistics::ImpulseStatistics RunStatistics::dropper_impulses() const
{
  ImpulseStatistics sum;
  for (const unsigned int i : layout.dropper_indices)
  {
    sum.count += impacts[i].count;
    sum.total += impacts[i].total;
    sum.max = std::max(sum.max, impacts[i].max);
  }
  return sum;
}

namespace
{
/**
 * One interval list as the time points pass: an interval opens at @p t when
 * @p open begins (@p since = t) and joins @p list when it ends (@p since =
 * NaN: none open).
 */
void track(const bool open, const double t, double& since, std::vector<Interval>& list)
{
  const bool was_open = !std::isnan(since);
  if (open && !was_open)
    since = t;
  else if (!open && was_open)
  {
    list.push_back({since, t});
    since = std::nan("");
  }
}
} // namespace

void RunStatistics::observe(const TimePoint& p)
{
  for (unsigned int k = 0; k < layout.pantographs.size(); ++k)
    if (layout.pantographs[k].has_contact())
    {
      forces[k].add(pantocat::contact_force(layout.pantographs[k], p), p.t,
                    k < p.x_p.size() ? p.x_p[k] : 0.);
      // Lost: it touches none of its contact wires.
      track(!in_contact(layout.pantographs[k], p), p.t, lost_since[k], losses[k]);
    }
  max_pos = std::max(max_pos, p.position_residual);
  max_vel = std::max(max_vel, p.velocity_residual);
  unsigned int slack = 0;
  for (const unsigned int i : layout.dropper_indices)
    slack += p.active[i] ? 0 : 1;
  max_slack = std::max(max_slack, slack);
  // An impact of constraint i: it closed at this time point. The impulses
  // of the constraints that held already (their share of a neighbour's
  // impact) join the total only.
  for (unsigned int i = 0; i < p.impulse.size(); ++i)
  {
    impacts[i].total += p.impulse[i];
    if (p.active[i] && !std::isnan(open_since[i]))
    {
      ++impacts[i].count;
      impacts[i].max = std::max(impacts[i].max, p.impulse[i]);
    }
  }
  for (unsigned int i = 0; i < p.active.size(); ++i)
    track(!p.active[i], p.t, open_since[i], intervals[i]);
  last_t = p.t;
}

void RunStatistics::finish()
{
  // Whatever is open at the end closes with the last time point.
  for (unsigned int k = 0; k < lost_since.size(); ++k)
    track(false, last_t, lost_since[k], losses[k]);
  for (unsigned int i = 0; i < open_since.size(); ++i)
    track(false, last_t, open_since[i], intervals[i]);
}

std::vector<std::vector<Interval>> RunStatistics::dropper_slack_intervals() const
{
  std::vector<std::vector<Interval>> result;
  for (const unsigned int i : layout.dropper_indices)
    result.push_back(intervals[i]);
  return result;
}

DropperSlackEvents RunStatistics::dropper_slack_events(const double from,
                                                       const double to) const
{
  DropperSlackEvents events;
  for (const unsigned int i : layout.dropper_indices)
  {
    const auto begins_inside = [&](const Interval& slack)
    { return slack.first >= from && slack.first <= to; };
    events.per_dropper.push_back(
        std::count_if(intervals[i].begin(), intervals[i].end(), begins_inside));
    events.total += events.per_dropper.back();
  }
  return events;
}

std::vector<Interval> RunStatistics::contact_loss_intervals() const
{
  for (unsigned int k = 0; k < layout.pantographs.size(); ++k)
    if (layout.pantographs[k].has_contact())
      return losses[k];
  return {};
}

std::vector<Interval> RunStatistics::contact_loss_intervals(const unsigned int k) const
{
  return layout.pantographs[k].has_contact() ? losses[k] : std::vector<Interval>{};
}

void RunStatistics::save(CheckpointOut& archive) const
{
  for (const ForceStatistics& f : forces)
    archive << f.max << f.min << f.mean << f.m2 << f.count << f.max_time << f.max_position
            << f.min_time << f.min_position;
  archive << max_pos << max_vel << last_t << intervals << open_since << max_slack
          << losses << lost_since;
  for (const ImpulseStatistics& s : impacts)
    archive << s.count << s.total << s.max;
}

void RunStatistics::resume(const SimulationLayout& l, CheckpointIn& archive)
{
  layout = l;
  forces.assign(l.pantographs.size(), {});
  for (ForceStatistics& f : forces)
    archive >> f.max >> f.min >> f.mean >> f.m2 >> f.count >> f.max_time >>
        f.max_position >> f.min_time >> f.min_position;
  archive >> max_pos >> max_vel >> last_t >> intervals >> open_since >> max_slack >>
      losses >> lost_since;
  impacts.assign(l.constraint_names.size(), {});
  for (ImpulseStatistics& s : impacts)
    archive >> s.count >> s.total >> s.max;
}
} // namespace pantocat
