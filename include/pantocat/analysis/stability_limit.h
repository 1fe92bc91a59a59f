#pragma once

#include <pantocat/system/semi_discrete_system.h>

#include <string>
#include <vector>

namespace pantocat
{
/**
 * The largest circular frequency omega_max of K x = omega^2 M x, computed
 * block by block (each body's M and K are banded) with the banded
 * generalized eigensolver. Constraints only lower the largest frequency
 * (interlacing), so 2/omega_max is a safe step-size limit for the
 * half-explicit method (Sec. 5.2).
 *
 * Compliant constraints (Constraint::is_compliant) are explicit forces of
 * that method and, engaged, add k_i G_i^T G_i to K: omega_max^2 is then
 * bounded by Weyl's inequality, all of them taken as engaged, by
 * omega_max^2(K, M) + compliant_frequency_bound(system), a local bound.
 */
double largest_circular_frequency(const SemiDiscreteSystem& system);

/**
 * An upper bound of what the springs of the compliant constraints add to
 * omega_max^2 at time @p t: the largest eigenvalue of M^-1 sum_i k_i G_i^T
 * G_i, which is that of A = Kc^1/2 G M^-1 G^T Kc^1/2 (Kc = diag k_i),
 * bounded by Gershgorin's theorem, max_i sum_j sqrt(k_i k_j) |G_i M^-1
 * G_j^T|. Only the constraints whose rows meet the column M^-1 G_i^T count
 * in row i (M^-1 G_i^T is solved locally for a banded M, on the row's own
 * unknowns for a diagonal one), so the bound is that of the most densely
 * coupled neighbourhood, the same for a section of 10 spans and of 160. For
 * one spring it is k G M^-1 G^T, exact. A moving constraint's row (penalty
 * contact) is taken at @p t; damping c_i is not included. 0 without
 * compliant constraints.
 */
double compliant_frequency_bound(const SemiDiscreteSystem& system, double t = 0.);

/**
 * G_i M^-1 G_i^T of every compliant constraint i at time @p t (0 for the
 * others): what a unit force on its row does to the acceleration of its gap.
 * With a banded mass, the columns M^-1 G_i^T are solved locally
 * (SparseDirectSolver::solve_local(): they decay away from the row), so all
 * of them cost O(m) and not O(n m).
 */
std::vector<double> compliant_mass_factors(const SemiDiscreteSystem& system,
                                           double t = 0.);

/// The step limit of the half-explicit method's explicit compliant damping.
struct ExplicitDampingLimit
{
  /// 2 / max_i c_i G_i M^-1 G_i^T [s]; infinite without compliant damping.
  double step = 0.;
  unsigned int constraint = 0; ///< the constraint i of the maximum
  double damping = 0.;         ///< its c_i [N s/m]
  double mass_factor = 0.;     ///< its G_i M^-1 G_i^T [1/kg]
};

/**
 * The half-explicit method takes a compliant constraint's damping force
 * -c_i dg/dt explicitly, with the velocity (v_{n-1} + v_n)/2 of (41), in
 * v_{n+1} = v_{n-1} + 2 dt a_n. On the damper alone the gap's rate then
 * follows r^2 + h r + h - 1 = 0, h = dt c_i G_i M^-1 G_i^T, with the roots
 * -1 and 1 - h: stable only for h <= 2. Returns the largest such dt over
 * the compliant constraints at time @p t (a necessary condition; the springs
 * and the wires' own frequencies lower the limit further).
 */
ExplicitDampingLimit explicit_damping_limit(const SemiDiscreteSystem& system,
                                            double t = 0.);

/**
 * For the step-size refusal: ", including the compliant constraints
 * (stiffest: '<name>', k = <k> N/m), explicit forces of this method that
 * raise omega_max by k G M^-1 G^T" if @p system has compliant constraints,
 * else "".
 */
std::string compliant_stiffness_note(const SemiDiscreteSystem& system);

/**
 * The step limit of the half-explicit method with the moving contact: the
 * constraint rows that change with time (the contact's G(t), G_t, G_tt) make
 * the method unstable below 2/omega_max (doc/stability.md). A step dt is
 * *stable* if perturbations of the run do not grow: growth_per_step() of the
 * product of the one-step maps (39)-(41) from t_0 over `steps` steps, the
 * constraints active as in the initial state, is at most 1 + growth_tolerance.
 *
 * Margin policy: a step is allowed if dt / margin is stable, i.e. dt is at
 * most margin times the largest stable step (critical step), found by
 * bisection to relative_accuracy.
 */
struct StepLimitOptions
{
  /// The allowed step is this fraction of the critical step.
  double margin = 0.95;
  /// Growth per step above 1 + this is unstable (e^2 over 1e4 steps); the
  /// estimate scatters by about 2e-5 where stable.
  double growth_tolerance = 2e-4;
  /// Steps of each power iteration.
  unsigned int steps = 2000;
  /// Of the critical step, in the bisection.
  double relative_accuracy = 0.01;
};

/// The result of half_explicit_step_limit().
struct HalfExplicitStepLimit
{
  double critical = 0.;        ///< the largest stable step found [s]
  double unstable = 0.;        ///< the smallest unstable step found [s]
  double growth_unstable = 0.; ///< growth per step at the step `unstable`
  double allowed = 0.;         ///< margin x critical [s]
  unsigned int tests = 0;      ///< power iterations done
};

/**
 * True if the step @p dt / margin is stable in the sense of StepLimitOptions
 * (one power iteration); @p growth receives the growth per step there.
 * @p active: the constraints active (rigid) or engaged (compliant) in the
 * state at @p t0 (DynamicState::active).
 */
bool half_explicit_step_allowed(const SemiDiscreteSystem& system,
                                const std::vector<bool>& active, double dt, double t0,
                                const StepLimitOptions& options = {},
                                double* growth = nullptr);

/**
 * The critical step below @p upper (an unstable step, e.g. dt / margin) by
 * bisection; the lower end starts at upper / 2 and is halved while unstable,
 * at most 10 times: if upper / 2^11 is still unstable, the result has
 * critical = allowed = 0, and `unstable`, `growth_unstable` that smallest
 * step and its growth (infinite where the one-step map overflows).
 */
HalfExplicitStepLimit half_explicit_step_limit(const SemiDiscreteSystem& system,
                                               const std::vector<bool>& active,
                                               double upper, double t0,
                                               const StepLimitOptions& options = {});

/// True if an active constraint's rows change with time (a moving contact).
bool has_moving_constraints(const SemiDiscreteSystem& system,
                            const std::vector<bool>& active);
} // namespace pantocat
