#pragma once

#include <pantocat/app/program_parameters.h>
#include <pantocat/coupling/contact_constraint.h>
#include <pantocat/pantograph/pantograph_model.h>
#include <pantocat/simulation/run_guard.h>
#include <pantocat/simulation/time_point.h>
#include <pantocat/space/catenary_discretisation.h>
#include <pantocat/system/semi_discrete_system.h>
#include <pantocat/time/time_integrator.h>

#include <memory>
#include <vector>

namespace pantocat
{
class CheckpointWriter;
class CheckpointReader;

/// Checkpoints of a run (issue 6): where to write them, how often, and where to resume.
struct CheckpointPlan
{
  const CheckpointWriter* writer = nullptr;
  unsigned int interval = 0; ///< steps between checkpoints; 0: none
  /// Continue from this checkpoint (its fingerprint already checked) instead of t_0.
  CheckpointReader* resume_from = nullptr;
  unsigned long stop_after_steps = 0; ///< stop as if killed (tests); 0: never
};

/**
 * One dynamic run of a scene (Sec. 6 for the paper's): builds the space
 * discretisation, the pantograph, the semi-discrete system of the scene's
 * effects (build_scene), the initial state and the integrator, then integrates
 * from x_p(0) to the final position and hands every time point to the
 * observers.
 */
class DynamicSimulation
{
public:
  explicit DynamicSimulation(const ProgramParameters& parameters);
  ~DynamicSimulation();

  struct Result
  {
    IntegratorStatistics integrator;
    double time_loop_seconds = 0.;
    double end_time = 0.;
    double stability_limit = 0.; ///< 2/omega_max [s]
    DynamicState final_state;    ///< the state at the end time
    GuardExtremes guards;        ///< drift, forces and energy seen by the guards
  };

  /**
   * Integrates; throws SimulationError if the run becomes unstable. With a
   * @p checkpoints plan, writes checkpoints every K steps (after the
   * observers have seen the step) and/or starts from one: the observers then
   * get resume() instead of start().
   */
  Result run(const std::vector<SimulationObserver*>& observers,
             const CheckpointPlan& checkpoints = {});

  const SemiDiscreteSystem& system() const { return coupled; }
  const SimulationLayout& layout() const { return layout_; }
  const DynamicState& initial_state() const { return initial; }
  const CatenaryDiscretisation& discretisation() const { return *space; }
  /// The step-size limit 2/omega_max of the explicit method for this system (computed
  /// once).
  double explicit_stability_limit() const;
  /**
   * Refuses (InputError naming the parameter, the value and the limit) a
   * half-explicit step above 2/omega_max, or warns if the user forces it.
   * run() calls it first; call it earlier to check before writing outputs.
   */
  void check_step_size() const;
  /**
   * Refuses (InputError) a grid whose spacing h = L/(N+1) is not below the
   * half-width eps of the smoothed load delta_eps (Sec. 4.1): the contact
   * then jumps between nodes, and the contact force comes out wrong (about
   * half the mean force at N+1 = 100) or blows up (N+1 = 50); doc/stability.md.
   */
  void check_load_resolution() const;
  /// Builds the time point of a state (gaps and residuals evaluated here).
  TimePoint time_point(const DynamicState& state) const;
  /// One line per effect of the scene (what is assembled), and the effects left out.
  const std::vector<std::string>& active_effects() const { return effects; }
  const std::vector<std::string>& inactive_effects() const { return left_out; }

private:
  ProgramParameters parameters;
  std::unique_ptr<CatenaryDiscretisation> space;
  std::unique_ptr<PantographModel> pantograph; ///< nullptr if the scene has none
  SemiDiscreteSystem catenary_only, coupled;
  ContactPointMotion motion;
  SimulationLayout layout_;
  std::vector<std::string> effects, left_out;
  std::vector<SparseRow> probe_rows; ///< rows of w_w at the probe positions
  DynamicState initial;
  mutable double stability_limit = 0.;
  mutable bool warned = false;
};

/// The scene's lumped-mass pantograph, or nullptr if it has none.
std::unique_ptr<PantographModel>
create_pantograph(const SceneParameters& scene, const PantographParameters& parameters);
} // namespace pantocat
