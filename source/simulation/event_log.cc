#include <pantocat/base/serialization.h>
#include <pantocat/simulation/event_log.h>

namespace pantocat
{
void EventLog::start(const SimulationLayout& l)
{
  layout = l;
  previous.clear();
  list.clear();
}

void EventLog::observe(const TimePoint& p)
{
  if (!previous.empty())
    for (unsigned int i = 0; i < p.active.size(); ++i)
      if (p.active[i] != previous[i])
      {
        const bool contact = layout.contact_owner(i) != nullptr;
        const char* kind = contact ? (p.active[i] ? "contact_return" : "contact_loss")
                                   : (p.active[i] ? "dropper_taut" : "dropper_slack");
        const double impulse = p.active[i] && !p.impulse.empty() ? p.impulse[i] : 0.;
        list.push_back({p.t, layout.constraint_names[i], kind, impulse});
      }
  previous = p.active;
}

void EventLog::save(CheckpointOut& archive) const
{
  archive << previous << static_cast<unsigned long>(list.size());
  for (const ConstraintEvent& e : list)
    archive << e.t << e.constraint << e.kind << e.impulse;
}

void EventLog::resume(const SimulationLayout& l, CheckpointIn& archive)
{
  layout = l;
  unsigned long size = 0;
  archive >> previous >> size;
  // One by one: a wrong size ends with the archive, not with a huge allocation.
  list.clear();
  for (unsigned long k = 0; k < size; ++k)
  {
    ConstraintEvent e;
    archive >> e.t >> e.constraint >> e.kind >> e.impulse;
    list.push_back(std::move(e));
  }
}
} // namespace pantocat
