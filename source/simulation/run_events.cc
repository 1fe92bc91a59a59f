#include <pantocat/simulation/run_events.h>

namespace pantocat
{
std::string event_kind(const SimulationLayout& layout, const unsigned int i,
                       const bool closes)
{
  if (layout.contact_owner(i) != nullptr)
    return closes ? "contact_return" : "contact_loss";
  return closes ? "dropper_taut" : "dropper_slack";
}

bool closes(const ConstraintEvent& event)
{
  return event.kind == "contact_return" || event.kind == "dropper_taut";
}

std::vector<ConstraintEvent> run_events(const SimulationLayout& layout,
                                        const IntegratorStatistics& integrator,
                                        const EventLog& log)
{
  if (!integrator.events_localised)
    return log.events();
  std::vector<ConstraintEvent> list;
  for (const SwitchEvent& e : integrator.localised_events)
    list.push_back({e.t, layout.constraint_names[e.constraint],
                    event_kind(layout, e.constraint, e.closes), e.impulse});
  return list;
}
} // namespace pantocat
