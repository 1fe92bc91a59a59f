#pragma once

#include <pantocat/simulation/guard_parameters.h>
#include <pantocat/simulation/time_point.h>
#include <pantocat/system/energy_functional.h>
#include <pantocat/system/semi_discrete_system.h>

namespace pantocat
{
/// What the guards saw over a run (summary.json "guards").
struct GuardExtremes
{
  double max_drift = 0.;           ///< max |g_i| over active constraints [m]
  double max_multiplier = 0.;      ///< max |lambda_i| [N]
  double max_energy_increase = 0.; ///< max E(t) - E(0) [J]
  double min_energy_increase = 0.; ///< min E(t) - E(0) [J] (damping, negative)
  double reference_force = 0.;     ///< F_ref [N]
  double reference_energy = 0.;    ///< E_ref [J]
};

/**
 * Stops a run that leaves the bounds of GuardParameters, with a
 * SimulationError naming the time, the step, the quantity, its value, the
 * bound and the constraint:
 *  - constraint drift: |g_i(t, q)| of an active constraint (position level of
 *    (38)) above the tolerance;
 *  - multipliers: |lambda_i| above bound x F_ref, F_ref = max(F_0, |lambda_i(0)|)
 *    (the pantograph's static force and the static dropper forces);
 *  - energy: E(t) - E(0) above bound x E_ref, with E = v^T M v/2 + q^T K q/2 - f^T q
 *    (SemiDiscreteSystem::energy) and E_ref = (T_c + T_w) L / 2, the strain energy of
 *    both wires at a root-mean-square slope of 1, where the linear model (2) has long
 *    lost its meaning. Damping only removes energy; the moving contact adds
 *    lambda_p v_p dw/dx per second, a few joules over a run. Evaluated every
 *    16th time point with EnergyFunctional (compact quadratic forms of M and
 *    K: its cost is under a third of a step of the explicit method).
 * An observer of the run (DynamicSimulation adds it last, after the outputs
 * have the time point), checkpointed with its extremes.
 */
class RunGuard : public SimulationObserver
{
public:
  RunGuard(const GuardParameters& parameters, const SemiDiscreteSystem& system,
           double reference_force, double reference_energy, const DynamicState& initial);

  void start(const SimulationLayout& layout) override;
  void observe(const TimePoint&) override {}
  void observe_state(const TimePoint& point, const DynamicState& state) override;
  void save(CheckpointOut& archive) const override;
  void resume(const SimulationLayout& layout, CheckpointIn& archive) override;

  const GuardExtremes& extremes() const { return seen; }

private:
  [[noreturn]] void stop(const TimePoint& point, const std::string& what) const;

  GuardParameters parameters;
  const SemiDiscreteSystem& system;
  EnergyFunctional energy; ///< E(t), compact (EnergyFunctional)
  SimulationLayout layout;
  double initial_energy;
  unsigned long points = 0;
  GuardExtremes seen;
};
} // namespace pantocat
