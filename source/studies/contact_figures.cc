#include <pantocat/scene/steady_arms.h>
#include <pantocat/simulation/run_events.h>
#include <pantocat/simulation/switch_episodes.h>
#include <pantocat/studies/contact_figures.h>
#include <pantocat/studies/packed_bytes.h>

#include <algorithm>
#include <limits>
#include <map>
#include <utility>

namespace pantocat
{
using packed::get;
using packed::put;

unsigned long ContactFigures::contact_events() const
{
  return std::count_if(events.begin(), events.end(),
                       [&](const StudyEvent& e) { return e.constraint == contact; });
}

void ContactFigures::pack(std::vector<char>& b) const
{
  for (const double x : {loss_percent, filtered_max, filtered_min, filtered_std,
                         min_unilateral_force, min_unilateral_time})
    put(b, x);
  packed::put_string(b, min_unilateral_constraint);
  put(b, contact);
  put(b, static_cast<std::uint64_t>(short_episodes));
  put(b, short_episode_time);
  put(b, static_cast<std::uint64_t>(events.size()));
  for (const StudyEvent& e : events)
  {
    put(b, e.t);
    put(b, e.constraint);
    put(b, static_cast<char>(e.closes));
  }
}

ContactFigures ContactFigures::unpack(const std::vector<char>& b, std::size_t& pos)
{
  ContactFigures f;
  for (double* x : {&f.loss_percent, &f.filtered_max, &f.filtered_min, &f.filtered_std,
                    &f.min_unilateral_force, &f.min_unilateral_time})
    *x = get<double>(b, pos);
  f.min_unilateral_constraint = packed::get_string(b, pos);
  f.contact = get<unsigned int>(b, pos);
  f.short_episodes = get<std::uint64_t>(b, pos);
  f.short_episode_time = get<double>(b, pos);
  f.events.resize(get<std::uint64_t>(b, pos));
  for (StudyEvent& e : f.events)
  {
    e.t = get<double>(b, pos);
    e.constraint = get<unsigned int>(b, pos);
    e.closes = get<char>(b, pos) != 0;
  }
  return f;
}

ContactFiguresRecorder::UnilateralMinimum::UnilateralMinimum(
    const SemiDiscreteSystem& system)
{
  for (unsigned int i = 0; i < system.n_constraints(); ++i)
    if (system.constraints[i]->is_unilateral())
      unilateral.push_back(i);
}

void ContactFiguresRecorder::UnilateralMinimum::start(const SimulationLayout& layout)
{
  names = layout.constraint_names;
}

void ContactFiguresRecorder::UnilateralMinimum::observe(const TimePoint& p)
{
  for (const unsigned int i : unilateral)
    if (!(p.lambda[i] >= force)) // the first value, or a smaller one
    {
      force = p.lambda[i];
      constraint = names[i];
      time = p.t;
    }
}

ContactFiguresRecorder::ContactFiguresRecorder(const CaseRunner& runner,
                                               const StatisticsParameters& statistics)
    : layout(runner.layout()), episode_resolution(statistics.episode_resolution),
      contact(
          statistics, runner.discretisation(), runner.system(),
          SteadyArms::positions(runner.case_data().scene, runner.case_data().catenary),
          0),
      minimum(runner.system())
{
}

std::vector<SimulationObserver*> ContactFiguresRecorder::observers()
{
  return {&contact, &log, &minimum};
}

ContactFigures
ContactFiguresRecorder::figures(const IntegratorStatistics& integrator) const
{
  ContactFigures f;
  const ContactForceStatistics& s = contact.result();
  f.loss_percent = s.raw.contact_loss_percent;
  if (s.filtered)
  {
    f.filtered_max = s.filtered->max;
    f.filtered_min = s.filtered->min;
    f.filtered_std = s.filtered->std;
  }
  f.min_unilateral_force = minimum.force;
  f.min_unilateral_constraint = minimum.constraint;
  f.min_unilateral_time = minimum.time;
  f.contact = layout.pantographs.at(0).contact;
  const std::vector<std::string>& names = layout.constraint_names;
  std::vector<StudyEvent> all;
  for (const ConstraintEvent& e : run_events(layout, integrator, log))
    all.push_back(
        {e.t,
         static_cast<unsigned int>(std::find(names.begin(), names.end(), e.constraint) -
                                   names.begin()),
         closes(e)});
  EpisodeEvents e = episode_events(all, episode_resolution);
  f.events.swap(e.events);
  f.short_episodes = e.short_episodes;
  f.short_episode_time = e.short_episode_time;
  return f;
}

namespace
{
/// A constraint's open intervals and the indices of the events that open and
/// close them (no_event: open at the start or at the end of the run).
struct OpenIntervals
{
  static constexpr std::size_t no_event = std::numeric_limits<std::size_t>::max();
  std::vector<Interval> intervals;
  std::vector<std::pair<std::size_t, std::size_t>> events;
};

/// The open intervals of each constraint of @p events (in time order; the
/// openings and closings of a constraint alternate).
std::map<unsigned int, OpenIntervals>
open_intervals(const std::vector<StudyEvent>& events)
{
  constexpr double infinity = std::numeric_limits<double>::infinity();
  constexpr std::size_t none = OpenIntervals::no_event;
  std::map<unsigned int, OpenIntervals> open;
  for (std::size_t i = 0; i < events.size(); ++i)
  {
    OpenIntervals& o = open[events[i].constraint];
    const double t = events[i].t;
    if (!events[i].closes)
    {
      o.intervals.push_back({t, infinity});
      o.events.push_back({i, none});
    }
    else if (!o.intervals.empty() && o.intervals.back().second == infinity)
    {
      o.intervals.back().second = t;
      o.events.back().second = i;
    }
    else // a closing first: open since the start of the run
    {
      o.intervals.push_back({-infinity, t});
      o.events.push_back({none, i});
    }
  }
  return open;
}
} // namespace

EpisodeEvents episode_events(const std::vector<StudyEvent>& events,
                             const double resolution)
{
  // The episodes of each constraint (switch_episodes(), as summary.json's);
  // those at least one resolution long keep their first opening and last
  // closing, the shorter ones are counted.
  EpisodeEvents result;
  std::vector<bool> kept(events.size(), false);
  for (const auto& [constraint, o] : open_intervals(events))
  {
    std::size_t first = 0;
    for (const SwitchEpisode& e : switch_episodes(o.intervals, resolution))
    {
      const std::size_t opening = o.events[first].first;
      const std::size_t closing = o.events[first + e.intervals - 1].second;
      first += e.intervals;
      const double length = e.span.second - e.span.first;
      if (length < resolution)
      {
        ++result.short_episodes;
        result.short_episode_time += length;
        continue;
      }
      for (const std::size_t i : {opening, closing})
        if (i != OpenIntervals::no_event)
          kept[i] = true;
    }
  }
  for (std::size_t i = 0; i < events.size(); ++i)
    if (kept[i])
      result.events.push_back(events[i]);
  return result;
}
} // namespace pantocat
