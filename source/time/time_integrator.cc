#include <pantocat/base/input_error.h>
#include <pantocat/time/dynamic_state_serialization.h>
#include <pantocat/time/integrator_registry.h>
#include <pantocat/time/time_integrator.h>

#include <algorithm>
#include <cmath>

namespace pantocat
{
std::unique_ptr<TimeIntegrator> create_time_integrator(const SemiDiscreteSystem& system,
                                                       const TimeIntegrationParameters& p)
{
  // Every method factorises or inverts a matrix of the system's size; deal.II's
  // matrices of size 0 have no storage (the methods read past it).
  if (system.n_dofs() == 0)
    throw InputError("Scene: the scene has no unknowns (both wires rigid, no pantograph "
                     "body), so there is nothing to integrate in time; make a wire "
                     "elastic (Scene/Messenger, Scene/Contact wire) or choose "
                     "Scene/Pantograph = two-mass | three-mass | mass-chain");
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

void TimeIntegrator::check_loaded(const dealii::Vector<double>& x,
                                  const unsigned int size, const std::string& name)
{
  if (x.size() != size)
    throw InputError(name + " has " + std::to_string(x.size()) + " entries, the system " +
                     std::to_string(size));
  if (!std::all_of(x.begin(), x.end(), [](const double e) { return std::isfinite(e); }))
    throw InputError(name + " holds a value that is not finite");
}

void TimeIntegrator::check_loaded(const DynamicState& s, const std::string& name) const
{
  if (!std::isfinite(s.t))
    throw InputError("the time of " + name + " is not finite");
  check_loaded(s.q, system.n_dofs(), "q of " + name);
  check_loaded(s.v, system.n_dofs(), "v of " + name);
  if (s.a.size() != 0)
    check_loaded(s.a, system.n_dofs(), "a of " + name);
  const dealii::Vector<double> lambda(s.lambda.begin(), s.lambda.end());
  check_loaded(lambda, system.n_constraints(), "lambda of " + name);
  check_loaded(s.active, "the active set of " + name);
}

void TimeIntegrator::check_loaded(const std::vector<bool>& active,
                                  const std::string& name) const
{
  if (active.size() != system.n_constraints())
    throw InputError(name + " has " + std::to_string(active.size()) +
                     " constraints, the system " +
                     std::to_string(system.n_constraints()));
}

void TimeIntegrator::check_loaded_steps(const unsigned long step_number) const
{
  if (stats.steps != step_number)
    throw InputError("the step counters disagree (" + std::to_string(stats.steps) +
                     " steps counted, step " + std::to_string(step_number) + ")");
}
} // namespace pantocat
