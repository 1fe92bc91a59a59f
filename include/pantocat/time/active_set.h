#pragma once

#include <pantocat/system/semi_discrete_system.h>

#include <string>
#include <vector>

namespace pantocat
{
/**
 * The active-set strategy of Sec. 5.3 for one time step t_n -> t_{n+1}.
 *
 * Start with J_{n+1} := J_n. After a trial step:
 *  - an inactive unilateral constraint with g_i(t_{n+1}, q_{n+1}) < 0 closes
 *    (contact or a taut dropper again). This is an inelastic impact
 *    (restitution 0): g = dg/dt = 0 hold at t_{n+1}, and the velocities jump
 *    by M^-1 G^T P with the impulse P that stops the approach
 *    (DynamicState::impulse). The closing constraint carries no force at
 *    t_{n+1}: it is held by a projection after the step or by the
 *    integrator's position- and velocity-level multipliers
 *    (ClosingConstraint); the next step starts with it active, and releases
 *    it if its force pulls. So no negative force of a unilateral constraint
 *    is ever accepted, and no impact is reported as a force;
 *  - a constraint of J_n with lambda_i < 0 becomes inactive (it separates:
 *    g = dg/dt = 0 at t_n and d2g/dt2 > 0 without it).
 *
 * Touching constraints. (36), (37) and g^(II) state complementarity level by
 * level. A constraint of J_n may have lambda_i < 0 when active and a negative
 * gap at t_{n+1} when released: no choice of "active" or "inactive" is
 * consistent, and the iteration of the paper cycles (seen at the re-tension
 * of dropper 2 at 48 m/s on several grids). With touching allowed, such a
 * constraint becomes *touching*: active on position and velocity level
 * (g = dg/dt = 0 at t_{n+1}, multipliers mu, eta), inactive on acceleration
 * level (g^(II)_i := lambda_i = 0). It just holds, without force; the next
 * step starts with it active again.
 *
 * Compliant constraints (Constraint::is_compliant) are forces, never active:
 * they are absent from active_indices() and force_indices(). For the implicit
 * methods their *engagement* (the linear law lambda = -k g - c dg/dt applies,
 * rather than lambda = 0) is iterated together with the active set: a
 * compliant unilateral constraint is engaged at t_{n+1} iff g < 0 and
 * -k g - c dg/dt > 0 there (accept() with the gap rates); a disagreement
 * toggles it and the step is repeated. Bilateral compliant constraints are
 * always engaged. Explicit methods (the half-explicit one) compute the force
 * from the state at t_n themselves and call accept() without rates: their
 * engagement is then left as start() set it.
 *
 * All violations are toggled together and the step is repeated; a set seen
 * before in the same step, or more than the allowed number of repetitions,
 * stops the run with a SimulationError that names time, step and constraints.
 *
 * Without touching (`allow_touching` false: the paper's iteration, for
 * tests), a closing constraint is active with whatever force it gets.
 */
class ActiveSetIteration
{
public:
  /// How a constraint that closes in a step (an impact) enters it.
  enum class ClosingConstraint : char
  {
    /**
     * Not in the step: the step is taken without it (it penetrates), and the
     * integrator projects positions and velocities at t_{n+1} onto the
     * holding constraints (ImpactProjection): the impact located to within
     * one step, its impulse kept apart from every force. For the GGL methods
     * (BDF-2, half-explicit), whose multipliers eta, mu would otherwise stop
     * a moving contact partly through G_t q, not by a jump of the velocities.
     */
    after_step,
    /**
     * Touching: held at t_{n+1} without force, by the integrator's own
     * projections (generalized-alpha: its index-3 multiplier would carry the
     * impact's momentum as a force of order 1/h).
     */
    touching
  };

  ActiveSetIteration(const SemiDiscreteSystem& system, unsigned int max_iterations,
                     ClosingConstraint closing = ClosingConstraint::after_step,
                     bool allow_touching = true);

  /// Begin a step from the active set J_n.
  void start(const std::vector<bool>& active_at_start);

  /**
   * Checks a trial step; returns true if it is accepted, otherwise updates
   * the active set for the repetition. @p gap_rates (dg/dt at t_{n+1} of
   * every constraint), if given, make the engagement of the compliant
   * constraints part of the check.
   */
  bool accept(const std::vector<double>& gaps_next, const std::vector<double>& lambda,
              double t, unsigned long step, const std::vector<double>& gap_rates = {});

  /// Constraints that hold at t_{n+1} (active or touching) and the engaged
  /// compliant ones: the flags of DynamicState::active.
  const std::vector<bool>& active() const;
  /// The engaged compliant constraints: forces by the linear law -k g - c dg/dt.
  const std::vector<unsigned int>& engaged_indices() const { return engaged; }
  /// Their indices: the constraints of g^(0) and g^(I).
  const std::vector<unsigned int>& active_indices() const { return indices; }
  /// The active constraints that carry a force: those of g^(II).
  const std::vector<unsigned int>& force_indices() const { return force; }
  /// Number of constraints whose state changed in the accepted step.
  unsigned int changes_in_step() const;
  /// True if a rigid unilateral constraint closed in the accepted step (an impact).
  bool impact_in_step() const;
  /**
   * The constraints that hold at t_{n+1} for an impact projection: the
   * active and touching ones and those closed after the step (after_step).
   */
  std::vector<unsigned int> holding_indices() const;
  unsigned int iterations_in_step() const { return visited.size(); }
  /// True if accept() reads the gap of constraint @p i in the current trial:
  /// a unilateral one that is inactive or compliant (the others hold or are bilateral).
  bool reads_gap(const unsigned int i) const
  {
    return unilateral[i] && (compliant[i] || current[i] == Status::inactive);
  }
  /// True if accept() reads the rate of constraint @p i: a compliant unilateral one.
  bool reads_rate(const unsigned int i) const { return unilateral[i] && compliant[i]; }

private:
  enum class Status : char
  {
    inactive,
    active,
    touching,
    engaged,  ///< a compliant constraint whose linear force law applies
    impacting ///< closed in this step, held by the projection after it
  };
  /// The status of compliant constraint @p i at t_{n+1} from its gap and rate.
  Status compliant_status(unsigned int i, double gap, double rate) const;
  void update_indices();
  std::string describe(const std::vector<Status>& set) const;

  const SemiDiscreteSystem& system;
  unsigned int max_iterations;
  ClosingConstraint closing;
  bool allow_touching;
  /// One byte per constraint (the loops per step read bytes, not bits).
  std::vector<char> at_start, holds, released;
  /// holds as the flags of active(), made again only after holds changed.
  mutable std::vector<bool> holds_flags;
  mutable bool holds_flags_current = false;
  /// The set that indices, force, engaged and holds were made for:
  /// update_indices() is skipped when a step starts from the same set.
  std::vector<char> indexed;
  /// Each constraint's kind, read once (the loops per step touch no constraint object).
  std::vector<char> unilateral, compliant;
  std::vector<unsigned int> unilateral_indices; ///< the only ones accept() can switch
  /// The status of each constraint when it holds: engaged if compliant, else active.
  std::vector<Status> held_status;
  /// Constraints that start() holds but J_n did not (bilateral ones not in J_n).
  unsigned int changes_at_start = 0;
  std::vector<Status> current;
  std::vector<Status> next; ///< accept()'s candidate, kept: no allocation per step
  std::vector<unsigned int> indices, force, engaged;
  std::vector<std::vector<Status>> visited;
};

/// d = c/k of a compliant constraint (its law divided by k), 0 for a rigid one.
double damping_ratio(const Constraint& constraint);

/**
 * Sets the forces of the compliant unilateral constraints in @p lambda to
 * max(0, lambda): an engaged spring's force solved from its law is positive up
 * to round-off, and a reported force is never negative.
 */
void clamp_compliant_forces(const SemiDiscreteSystem& system,
                            std::vector<double>& lambda);
} // namespace pantocat
