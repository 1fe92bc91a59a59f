#pragma once

#include <pantocat/analysis/static_elasticity.h>
#include <pantocat/analysis/static_equilibrium.h>
#include <pantocat/simulation/case.h>
#include <pantocat/simulation/catenary_design.h>
#include <pantocat/simulation/contact_statistics.h>
#include <pantocat/simulation/run_guard.h>
#include <pantocat/simulation/time_point.h>
#include <pantocat/space/catenary_discretisation.h>
#include <pantocat/system/energy_functional.h>
#include <pantocat/system/semi_discrete_system.h>
#include <pantocat/time/time_integrator.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace pantocat
{
struct HalfExplicitStepLimit;
class CheckpointWriter;
class CheckpointReader;

/// Checkpoints of a run: where to write them, how often, and where to resume.
struct CheckpointPlan
{
  const CheckpointWriter* writer = nullptr;
  unsigned int interval = 0; ///< steps between checkpoints; 0: none
  /// Continue from this checkpoint (its fingerprint already checked) instead of t_0.
  CheckpointReader* resume_from = nullptr;
  unsigned long stop_after_steps = 0; ///< stop as if killed (tests); 0: never
};

/**
 * What a run measures at every time point besides the constraints' forces
 * and gaps (an output's request, not part of the case): the contact wire at
 * probe positions and the energy of the system.
 */
struct Measurements
{
  std::vector<double> probe_positions; ///< x [m] of w_w probes
  bool energy = false;
};

/**
 * The one way to run a case. Builds, once, the space discretisation, the
 * scene's semi-discrete system with every pantograph and contact
 * (build_scene), and the consistent initial state; run() makes the
 * integrator from the registry, integrates from t = 0 to the case's end time
 * and hands every time point to the observers. The program's modes and every
 * study run cases only through it; nothing else builds a scene.
 */
class CaseRunner
{
public:
  /// Throws InputError for a case the grid cannot carry (droppers, probes).
  explicit CaseRunner(const Case& c, const Measurements& measurements = {});
  ~CaseRunner();

  struct Result
  {
    IntegratorStatistics integrator;
    double time_loop_seconds = 0.;
    double end_time = 0.;
    double stability_limit = 0.; ///< 2/omega_max [s] (explicit integrators only)
    DynamicState final_state;    ///< the state at the end time
    GuardExtremes guards;        ///< drift, forces and energy seen by the guards
  };

  /**
   * Refuses, before anything is written, what the run cannot do: a step above
   * the stability limit of an explicit integrator (step_size_problem(); a warning if
   * forced), a grid that does not resolve the smoothed load of a moving contact.
   */
  void check() const;

  /**
   * Integrates; throws SimulationError if the run becomes unstable. With a
   * @p checkpoints plan, writes checkpoints every K steps (after the
   * observers have seen the step) and/or starts from one: the observers then
   * get resume() instead of start().
   */
  Result run(const std::vector<SimulationObserver*>& observers,
             const CheckpointPlan& checkpoints = {});

  /**
   * The catenary at rest under its loads and the pantographs' initial
   * contact forces (or moving forces) at their initial positions (Sec. 2.2,
   * Fig. 5): step 1 of the consistent initial state, in the numbering of
   * system() restricted to the catenary.
   */
  StaticEquilibrium static_catenary() const;

  /**
   * The static check of @p parameters (enabled(), checked): the elasticity
   * of the catenary alone, without the pantographs and their loads
   * (static_elasticity() on the catenary's system, the designed one if the
   * section needed a design).
   */
  StaticElasticity static_elasticity(const ElasticityParameters& parameters) const;

  /**
   * The case as it runs; its time step is time_step(), which may be shorter
   * than the one asked for.
   */
  const Case& case_data() const { return data; }
  /**
   * The step the run takes: t_e / n with n = ceil(t_e / dt) for the step dt
   * asked for, so that the last step ends exactly at the end time (a
   * pantograph exactly at its final position, Sec. 6). Equals dt when dt
   * divides t_e; otherwise shorter by less than dt / n.
   */
  double time_step() const { return data.time_integration.time_step; }
  /// The number of steps n of run().
  unsigned long number_of_steps() const;
  /// The static design of the section, if it needed one (needs_design()).
  const std::optional<CatenaryDesignResult>& design() const { return design_; }
  const SemiDiscreteSystem& system() const;
  const SimulationLayout& layout() const { return layout_; }
  const DynamicState& initial_state() const { return initial; }
  /// The discretisation of the (first) section.
  const CatenaryDiscretisation& discretisation() const { return *spaces.front(); }
  /**
   * Where the run's contact statistics record the uplift: the contact wire
   * at every dropper of every section, and at every steady arm with its
   * position along the line.
   */
  UpliftPoints uplift_points() const;
  /// The supports along the line, increasing (an overlap's shared supports once).
  std::vector<double> support_positions() const;
  /// The positions along the line of every dropper, in the order of the droppers'
  /// constraints.
  std::vector<double> dropper_positions() const;
  /// The tension sections along the line as designed (one for a single section).
  const std::vector<CatenaryParameters>& sections() const { return sections_; }
  /// w_w(@p x) of the contact wire in state @p q of system() (0 if it is rigid).
  double contact_wire_displacement(const dealii::Vector<double>& q, double x) const;
  /// The step-size limit 2/omega_max of the explicit method (computed once).
  double explicit_stability_limit() const;
  /**
   * Why the step is too large for an explicit integrator ("" if it is not):
   * above 2/omega_max, or (half-explicit with a moving contact) above the
   * limit of half_explicit_step_limit() with StepLimitOptions' margin
   * (doc/stability.md). Computed once: one power iteration for a step that is
   * allowed, a bisection of about eight for one that is not.
   */
  std::string step_size_problem() const;
  /**
   * Builds the time point of a state (gaps and residuals evaluated here).
   * The last line of defence of the outputs: a unilateral constraint only
   * pushes (lambda_i >= 0, Sec. 5.3; a compliant one by its law max(0, ...)),
   * so a state with a negative force of a unilateral constraint is an
   * internal error of the integrator's step. It throws a SimulationError
   * that names the time, the constraint and its force, before any observer
   * sees the time point: such a force is never written, nor clamped.
   */
  TimePoint time_point(const DynamicState& state) const;
  /// The constraint rows fill_time_point() keeps from one time point to the next.
  struct TimePointWorkspace
  {
    /// Per constraint; the constant ones evaluated at the first time point only.
    std::vector<ConstraintState> rows;
    /// Each constraint's kind, read at the first time point.
    std::vector<char> time_dependent, compliant, unilateral;
    /// E(t) of the energy column, made at the first time point that needs it.
    std::optional<EnergyFunctional> energy;
  };
  /**
   * time_point() into @p point, reusing its vectors and the constraint rows
   * of @p workspace: what the time loop calls every step, without
   * allocations, evaluating only the constraints that depend on t.
   */
  void fill_time_point(const DynamicState& state, TimePoint& point,
                       TimePointWorkspace& workspace,
                       const std::vector<ConstraintState>* known_rows = nullptr) const;
  /// One line per effect of the scene (what is assembled), and the effects left out.
  const std::vector<std::string>& active_effects() const;
  const std::vector<std::string>& inactive_effects() const;

private:
  struct Scene;
  /// Makes sections_ and spaces: the line's sections designed (the first one's
  /// design kept in design_), a single section also installed.
  void design_sections();
  /// The guards with F_ref from the pantographs and initial forces, E_ref = (T_c + T_w) L
  /// / 2.
  RunGuard make_guard() const;
  void check_step_size() const;
  /**
   * The half-explicit method's explicit compliant damping above its limit
   * (explicit_damping_limit()): the reason for step_size_problem(), and the
   * refusal naming the damping parameter in damping_refusal; "" if within.
   */
  std::string explicit_damping_problem() const;
  /// The reason for step_size_problem() when no step is stable (@p l.critical = 0).
  std::string no_stable_step(const HalfExplicitStepLimit& l, unsigned int steps) const;
  void check_load_resolution() const;
  /// x_p(t_0) of the first pantograph in contact (NaN if none).
  double initial_contact_position() const;
  /// Throws the internal error of time_point() if a unilateral force of @p s is < 0.
  void require_pushing_unilateral_forces(const DynamicState& s,
                                         const std::vector<char>& unilateral) const;

  Case data;
  double asked_time_step; ///< Time integration/Time step as given
  std::optional<CatenaryDesignResult> design_;
  /// The tension sections as designed and installed, and their discretisations.
  std::vector<CatenaryParameters> sections_;
  std::vector<std::unique_ptr<CatenaryDiscretisation>> spaces;
  std::unique_ptr<Scene> scene;
  SimulationLayout layout_;
  std::vector<SparseRow> probe_rows; ///< rows of w_w at the probe positions
  DynamicState initial;
  mutable double stability_limit = 0.;
  mutable bool warned = false;
  mutable bool step_size_checked = false;
  mutable std::string step_size_reason;
  mutable std::string damping_refusal; ///< see explicit_damping_problem()
};
} // namespace pantocat
