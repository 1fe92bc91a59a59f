#include <pantocat/base/input_error.h>
#include <pantocat/base/serialization.h>
#include <pantocat/simulation/run_guard.h>

#include <cmath>
#include <iomanip>
#include <sstream>

namespace pantocat
{
RunGuard::RunGuard(const GuardParameters& p, const SemiDiscreteSystem& system,
                   const double reference_force, const double reference_energy,
                   const DynamicState& initial)
    : parameters(p), system(system), energy(system),
      initial_energy(energy(initial.q, initial.v, initial.t))
{
  seen.reference_force = reference_force;
  seen.reference_energy = reference_energy;
}

void RunGuard::start(const SimulationLayout& l)
{
  layout = l;
  points = 0;
}

void RunGuard::stop(const TimePoint& p, const std::string& what) const
{
  std::ostringstream m;
  m << "unstable: " << what << " at t = " << std::setprecision(10) << p.t << " s (step "
    << points - 1 << ")";
  throw SimulationError(m.str());
}

void RunGuard::observe_state(const TimePoint& p, const DynamicState& s)
{
  ++points;
  for (unsigned int i = 0; i < p.gap.size(); ++i)
  {
    // A compliant constraint's gap is its spring's deflection, not a drift.
    const bool rigid_and_active = p.active[i] && !system.constraints[i]->is_compliant();
    const double drift = rigid_and_active ? std::abs(p.gap[i]) : 0.;
    seen.max_drift = std::max(seen.max_drift, drift);
    if (drift > parameters.drift_tolerance)
    {
      std::ostringstream m;
      m << "constraint drift |g| = " << drift << " m of " << layout.constraint_names[i]
        << " exceeds Guards/Constraint drift tolerance = " << parameters.drift_tolerance
        << " m";
      stop(p, m.str());
    }
    const double force = std::abs(p.lambda[i]);
    seen.max_multiplier = std::max(seen.max_multiplier, force);
    if (force > parameters.multiplier_bound * seen.reference_force)
    {
      std::ostringstream m;
      m << "force |lambda| = " << force << " N of " << layout.constraint_names[i]
        << " exceeds Guards/Multiplier bound = " << parameters.multiplier_bound
        << " x F_ref = " << parameters.multiplier_bound * seen.reference_force << " N";
      stop(p, m.str());
    }
  }
  if ((points - 1) % 16 != 0)
    return;
  const double increase = energy(s.q, s.v, s.t) - initial_energy;
  seen.max_energy_increase = std::max(seen.max_energy_increase, increase);
  seen.min_energy_increase = std::min(seen.min_energy_increase, increase);
  if (!std::isfinite(increase))
    stop(p, "the energy E(t) - E(0) is not finite (" + std::to_string(increase) +
                " J): the state is too large for its energy to be computed");
  if (!(increase <= parameters.energy_bound * seen.reference_energy))
  {
    std::ostringstream m;
    m << "energy E(t) - E(0) = " << increase
      << " J exceeds Guards/Energy bound = " << parameters.energy_bound
      << " x E_ref = " << parameters.energy_bound * seen.reference_energy << " J";
    stop(p, m.str());
  }
}

void RunGuard::save(CheckpointOut& archive) const
{
  archive << points << seen.max_drift << seen.max_multiplier << seen.max_energy_increase
          << seen.min_energy_increase;
}

void RunGuard::resume(const SimulationLayout& l, CheckpointIn& archive)
{
  layout = l;
  archive >> points >> seen.max_drift >> seen.max_multiplier >>
      seen.max_energy_increase >> seen.min_energy_increase;
}
} // namespace pantocat
