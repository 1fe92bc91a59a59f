#include <pantocat/scene/steady_arms.h>
#include <pantocat/simulation/run_events.h>
#include <pantocat/studies/contact_figures.h>
#include <pantocat/studies/packed_bytes.h>

#include <algorithm>

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
/// The next event of the constraint of @p events[i] after i, or events.size().
std::size_t next_of_same(const std::vector<StudyEvent>& events, const std::size_t i,
                         const std::vector<bool>& dropped)
{
  for (std::size_t j = i + 1; j < events.size(); ++j)
    if (!dropped[j] && events[j].constraint == events[i].constraint)
      return j;
  return events.size();
}
} // namespace

EpisodeEvents episode_events(const std::vector<StudyEvent>& events,
                             const double resolution)
{
  std::vector<bool> dropped(events.size(), false);
  // The inner reclosures of each episode: a closing and the next opening.
  for (std::size_t i = 0; i < events.size(); ++i)
    if (events[i].closes)
      if (const std::size_t j = next_of_same(events, i, dropped);
          j < events.size() && !events[j].closes &&
          events[j].t - events[i].t < resolution)
        dropped[i] = dropped[j] = true;
  // Episodes shorter than the resolution: an opening and its closing.
  EpisodeEvents result;
  for (std::size_t i = 0; i < events.size(); ++i)
    if (!dropped[i] && !events[i].closes)
      if (const std::size_t j = next_of_same(events, i, dropped);
          j < events.size() && events[j].closes && events[j].t - events[i].t < resolution)
      {
        dropped[i] = dropped[j] = true;
        ++result.short_episodes;
        result.short_episode_time += events[j].t - events[i].t;
      }
  for (std::size_t i = 0; i < events.size(); ++i)
    if (!dropped[i])
      result.events.push_back(events[i]);
  return result;
}
} // namespace pantocat
