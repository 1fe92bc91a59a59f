#pragma once

#include <pantocat/base/checkpoint_archive.h>
#include <pantocat/time/dynamic_state.h>

#include <deal.II/base/numbers.h>

#include <string>
#include <vector>

namespace pantocat
{
/// What the outputs know about one pantograph of a run.
struct PantographLayout
{
  std::string name;          ///< "pantograph", or "pantograph k" with several
  std::string column_suffix; ///< "" with one pantograph, "[k]" with several
  std::string model;         ///< "two-mass", ..., "moving force", "absent"
  /**
   * Its contact constraint; invalid_unsigned_int without a body in contact.
   * On a line of several sections: its contact with the wire it touches at
   * t = 0.
   */
  unsigned int contact = dealii::numbers::invalid_unsigned_int;
  /// Every contact constraint of it: one per contact wire it can touch
  /// (one per section of the line), in the order of the sections.
  std::vector<unsigned int> wire_contacts;
  std::vector<std::string> coordinates; ///< names of its q_MBS ("w_p1", ...)
  unsigned int first_coordinate = 0;    ///< where they start in TimePoint::pantograph
  double static_force = 0.;             ///< F_0 of its model, or the moving force [N]
  double initial_contact_force = 0.;    ///< lambda_p(0) [N]

  bool has_contact() const { return contact != dealii::numbers::invalid_unsigned_int; }
};

/// What the outputs know about a dynamic run: names and roles of the constraints.
struct SimulationLayout
{
  std::vector<std::string> constraint_names; ///< in system order: droppers, then contacts
  /// Every pantograph, in order; numbers of pantographs and contacts are data.
  std::vector<PantographLayout> pantographs;
  std::vector<unsigned int> dropper_indices;
  std::vector<double> probe_positions; ///< x of TimePoint::probes [m]
  bool energy = false;                 ///< TimePoint::energy is computed

  /// True if some pantograph is in contact with the wire.
  bool has_contact() const;
  /// The pantograph whose contact is constraint @p i, or nullptr.
  const PantographLayout* contact_owner(unsigned int i) const;
  /// The pantographs in contact with the wire.
  std::vector<const PantographLayout*> contacts() const;
};

/// One reported time point of a dynamic run.
struct TimePoint
{
  double t = 0.;
  std::vector<double> x_p;    ///< position of each pantograph [m]
  std::vector<double> lambda; ///< per constraint [N]
  std::vector<double> gap;    ///< g_i(t, q) per constraint [m]
  std::vector<bool> active;   ///< per constraint
  /// Impulse [N s] per constraint of an impact since the previous time point
  /// (DynamicState::impulse); empty without one.
  std::vector<double> impulse;
  std::vector<double> pantograph; ///< q_MBS of every pantograph body, in order
  double position_residual = 0.;  ///< max |g_i| over active constraints
  double velocity_residual = 0.;  ///< max |dg_i/dt| over active constraints
  std::vector<double> probes;     ///< w_w at the probe positions [m]
  double energy = 0.;             ///< if SimulationLayout::energy [J]
};

/// The contact force of pantograph @p p at @p point: the sum over its contact wires.
double contact_force(const PantographLayout& p, const TimePoint& point);
/// True if pantograph @p p touches some contact wire at @p point.
bool in_contact(const PantographLayout& p, const TimePoint& point);

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
   * Checkpoints: save() writes what the observer needs to continue
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
