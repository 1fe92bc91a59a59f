#include <pantocat/base/input_error.h>
#include <pantocat/time/dynamic_state_serialization.h>
#include <pantocat/time/integrator_registry.h>
#include <pantocat/time/time_integrator.h>

namespace pantocat
{
std::unique_ptr<TimeIntegrator> create_time_integrator(const SemiDiscreteSystem& system,
                                                       const TimeIntegrationParameters& p)
{
  return integrator_entry(p.integrator).create(system, p);
}

void TimeIntegrator::save(CheckpointOut&) const
{
  throw SimulationError("the " + name() + " integrator cannot write checkpoints");
}

void TimeIntegrator::load(CheckpointIn&)
{
  throw SimulationError("the " + name() + " integrator cannot resume from checkpoints");
}

void TimeIntegrator::save_statistics(CheckpointOut& archive) const
{
  archive << stats.steps << stats.active_set_iterations << stats.active_set_changes;
}

void TimeIntegrator::load_statistics(CheckpointIn& archive)
{
  archive >> stats.steps >> stats.active_set_iterations >> stats.active_set_changes;
}
} // namespace pantocat
