#pragma once

#include <pantocat/base/checkpoint_archive.h>
#include <pantocat/system/semi_discrete_system.h>
#include <pantocat/time/dynamic_state.h>
#include <pantocat/time/time_integration_parameters.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace pantocat
{
/// A switch of unilateral constraint @p constraint located in time by an integrator.
struct SwitchEvent
{
  double t = 0.;
  unsigned int constraint = 0;
  bool closes = false; ///< true: becomes active (impact); false: released
  double impulse = 0.; ///< of the impact [N s] (closing events)
};

/// Work counters of an integrator run.
struct IntegratorStatistics
{
  unsigned long steps = 0;
  unsigned long active_set_iterations = 0; ///< repeated trial steps (Sec. 5.3)
  unsigned long active_set_changes = 0;    ///< constraints switched in accepted steps
  /// Switches located in time (root finding); empty for step-resolved integrators.
  bool events_localised = false;
  std::vector<SwitchEvent> localised_events;
  /// Further counters of the integrator (e.g. IDA's), name and value.
  std::vector<std::pair<std::string, long>> counters;
};

/**
 * A fixed-step integrator of the semi-discrete constrained system (35). It
 * sees only the SemiDiscreteSystem: matrices, loads and constraint rows.
 *
 * Usage: initialize() with a consistent state (q, v, a, lambda at t_0), then
 * advance() repeatedly. latest() is the newest time point at which q, v and
 * lambda are all known: for the half-explicit method the multipliers of t_n
 * are computed in the step that leaves t_n, so latest() lags one step behind
 * the newest positions until finish() computes the last multipliers.
 */
class TimeIntegrator
{
public:
  explicit TimeIntegrator(const SemiDiscreteSystem& system) : system(system) {}
  virtual ~TimeIntegrator() = default;

  virtual std::string name() const = 0;
  virtual void initialize(const DynamicState& initial) = 0;
  virtual void advance() = 0;
  /// Completes the last time point (multipliers) after the final advance().
  virtual void finish() {}
  virtual const DynamicState& latest() const = 0;
  /// True if latest() is the time point before the newest positions (see above).
  virtual bool multipliers_lag_one_step() const { return false; }
  /**
   * The constraints' rows (G, z, G_t, z_t, ...) at latest().t when the
   * integrator has evaluated them there anyway, else null: the time point
   * then does not evaluate the moving contacts again.
   */
  virtual const std::vector<ConstraintState>* constraint_states_at_latest() const
  {
    return nullptr;
  }
  /// Time of the newest positions.
  virtual double time() const = 0;

  const IntegratorStatistics& statistics() const { return stats; }

  /**
   * Checkpoints: save() writes the method's whole internal state
   * after a step (history, auxiliary variables, active set, counters), so that
   * load() into an integrator made for the same system and parameters, after
   * initialize(), continues bit for bit as if never stopped. The default
   * refuses with a SimulationError (IDA: its history lives in SUNDIALS).
   */
  virtual void save(CheckpointOut& archive) const;
  virtual void load(CheckpointIn& archive);

protected:
  /// The counters of stats, for save() and load() of the derived methods.
  void save_statistics(CheckpointOut& archive) const;
  void load_statistics(CheckpointIn& archive);

  /**
   * Plausibility of what load() read (a checkpoint of another system, or
   * one damaged in a way its checksum missed, must not run on): @p x has
   * @p size entries, all finite; throws an InputError naming @p name.
   */
  static void check_loaded(const dealii::Vector<double>& x, unsigned int size,
                           const std::string& name);
  /// The same for a state: t finite, q and v of n_dofs() entries, a of
  /// n_dofs() or none, lambda and the active set of n_constraints().
  void check_loaded(const DynamicState& state, const std::string& name) const;
  /// The same for an active set of n_constraints() flags.
  void check_loaded(const std::vector<bool>& active, const std::string& name) const;
  /// The counter of steps that load() read equals @p step_number, the method's own.
  void check_loaded_steps(unsigned long step_number) const;

  const SemiDiscreteSystem& system;
  IntegratorStatistics stats;
};

std::unique_ptr<TimeIntegrator>
create_time_integrator(const SemiDiscreteSystem& system,
                       const TimeIntegrationParameters& p);
} // namespace pantocat
