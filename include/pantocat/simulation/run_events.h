#pragma once

#include <pantocat/simulation/event_log.h>
#include <pantocat/simulation/time_point.h>
#include <pantocat/time/time_integrator.h>

#include <string>
#include <vector>

namespace pantocat
{
/// contact_return | contact_loss (a pantograph's contact) or dropper_taut |
/// dropper_slack: the kind of a switch of constraint @p i that @p closes or opens.
std::string event_kind(const SimulationLayout& layout, unsigned int i, bool closes);

/// True if @p event closes its constraint: the contact returns, a dropper re-tensions.
bool closes(const ConstraintEvent& event);

/**
 * Every switch of the unilateral constraints in a run, in time order: those
 * the integrator located in time (IDA's root finding) if it locates them,
 * else those @p log recorded at step resolution.
 */
std::vector<ConstraintEvent> run_events(const SimulationLayout& layout,
                                        const IntegratorStatistics& integrator,
                                        const EventLog& log);
} // namespace pantocat
