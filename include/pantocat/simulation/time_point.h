#pragma once

#include <pantocat/base/checkpoint_archive.h>
#include <pantocat/time/dynamic_state.h>

#include <deal.II/base/numbers.h>

#include <string>
#include <vector>

namespace pantocat
{
/// What the outputs know about a dynamic run: names and roles of the constraints.
struct SimulationLayout
{
  std::vector<std::string> constraint_names; ///< in system order: droppers, then contact
  std::vector<std::string> pantograph_coordinates;
  /// The pantograph-wire contact; invalid_unsigned_int if the scene has none.
  unsigned int contact_index = dealii::numbers::invalid_unsigned_int;
  std::vector<unsigned int> dropper_indices;
  std::vector<double> probe_positions; ///< x of TimePoint::probes [m]
  bool energy = false;                 ///< TimePoint::energy is computed

  bool has_contact() const
  {
    return contact_index != dealii::numbers::invalid_unsigned_int;
  }
};

/// One reported time point of a dynamic run.
struct TimePoint
{
  double t = 0.;
  double x_p = 0.;
  std::vector<double> lambda;     ///< per constraint [N]
  std::vector<double> gap;        ///< g_i(t, q) per constraint [m]
  std::vector<bool> active;       ///< per constraint
  std::vector<double> pantograph; ///< q_MBS
  double position_residual = 0.;  ///< max |g_i| over active constraints
  double velocity_residual = 0.;  ///< max |dg_i/dt| over active constraints
  std::vector<double> probes;     ///< w_w at the probe positions [m]
  double energy = 0.;             ///< if SimulationLayout::energy [J]
};

/// Receives the time points of a run (time series, statistics, plots, ...).
class SimulationObserver
{
public:
  virtual ~SimulationObserver() = default;
  virtual void start(const SimulationLayout&) {}
  virtual void observe(const TimePoint& point) = 0;
  /**
   * Called right after observe(@p point) with the state behind it: positions
   * q and velocities v of the semi-discrete system (35), valid only during the
   * call. For observers that need the wires themselves (VTU frames, dropper
   * uplift); they get the system and discretisation when they are made.
   */
  virtual void observe_state(const TimePoint& /*point*/, const DynamicState& /*state*/) {}
  virtual void finish() {}
  /**
   * Checkpoints (issue 6): save() writes what the observer needs to continue
   * the run from the last time point it saw (accumulators, the length of its
   * files); resume() replaces start() when a run continues from a
   * checkpoint and reads the same, so that the outputs come out as those of
   * the uninterrupted run. The defaults refuse with a SimulationError: an
   * observer that keeps state must say how it continues.
   */
  virtual void save(CheckpointOut& archive) const;
  virtual void resume(const SimulationLayout& layout, CheckpointIn& archive);
  /// False for an observer without state that a checkpoint skips (resume() calls
  /// start()).
  virtual bool checkpointed() const { return true; }
};
} // namespace pantocat
