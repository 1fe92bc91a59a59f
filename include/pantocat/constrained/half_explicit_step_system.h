#pragma once

#include <pantocat/constrained/constrained_operator.h>
#include <pantocat/system/semi_discrete_system.h>

#include <deal.II/lac/vector.h>

#include <memory>
#include <vector>

namespace pantocat
{
/**
 * The linear algebra of one step t_n -> t_{n+1} = t_n + h of the
 * half-explicit method (39)-(41) (Sec. 5.2) for the GGL-stabilised system
 * (38), in the two levels the method writes:
 *
 *  - the acceleration level (39) with the smoothing (41): with W = M + h/2 D,
 *
 *        W a_n = f(t_n) - K q_n - D (v_{n-1} + v_n)/2 + G(t_n)^T lambda_n,
 *        G a_n + 2 G_t v_n + G_tt q_n + z_tt = 0 at t_n on the force set,
 *
 *    where lambda_n of the compliant constraints is given (explicit forces of
 *    the method), and the unconstrained part of (40),
 *    v* = v_{n-1} + 2 h a_n, q* = q_n + h (v_n + v*)/2 (predict_unconstrained());
 *
 *  - the position and velocity level (40): eta, mu on the active set with
 *
 *        q_{n+1} = q* + M^-1 (h^2 G(t_n)^T eta + h G_t(t_{n+1/2})^T eta
 *                  + h G(t_{n+1/2})^T mu),
 *        v_{n+1} = v* + 2 h M^-1 G(t_n)^T eta,
 *        g(q_{n+1}, t_{n+1}) = 0,  dg/dt(q_{n+1}, v_{n+1}, t_{n+1}) = 0.
 *
 * The method (HalfExplicitIntegrator) states the step, the active-set
 * strategy, the compliant forces and the impacts; how these two levels are
 * solved is the implementation's business (make_half_explicit_step_system()):
 * the reference applies full factorisations of W and M to every column and
 * solves the multiplier systems densely; the fast one sweeps the forces and
 * the prediction in one pass, splits the constraints into those with
 * constant rows (Schur complements factorised once per active set, or one by
 * one when no two share an unknown) bordered by the moving ones, and leaves
 * out the corrections of fixed constraints that are settled, in O(n + m).
 */
class HalfExplicitStepSystem
{
public:
  /// What a step starts from and where its results go (kept by reference for the step).
  struct Step
  {
    double t = 0.;            ///< t_n
    unsigned long number = 0; ///< the step's number since the start
    const dealii::Vector<double>*q = nullptr, *v = nullptr, *v_previous = nullptr;
    /// The constraints' rows at t_n, t_{n+1/2} and t_{n+1}.
    const std::vector<ConstraintState>*at_n = nullptr, *at_half = nullptr,
          *at_next = nullptr;
    /**
     * The active sets at t_{n-1} and t_n, when the two-step history is that
     * of the method's own steps since at least two steps (no start, new
     * v_{n-1} or impact since): a fixed constraint active in both whose force
     * is taken in the step has consistent history, which an implementation
     * may use (its eta, mu vanish in exact arithmetic). Else nullptr.
     */
    const std::vector<bool>*active_before = nullptr, *active_now = nullptr;
    /// a_n, q_{n+1}, v_{n+1}, lambda_n (one per constraint; the compliant ones'
    /// forces on entry) and the gaps g_i(q_{n+1}, t_{n+1}).
    dealii::Vector<double>*a = nullptr, *q_next = nullptr, *v_next = nullptr;
    std::vector<double>*lambda = nullptr, *gaps = nullptr;
  };

  HalfExplicitStepSystem(const SemiDiscreteSystem& system, double h)
      : system(system), h(h)
  {
  }
  virtual ~HalfExplicitStepSystem() = default;

  /// The step size h (negative to step backwards).
  double time_step() const { return h; }
  /// Changes h (W = M + h/2 D is factorised again).
  virtual void set_time_step(double time_step) = 0;

  /// Starts a step: @p step is kept until finish_step().
  virtual void start(const Step& step) = 0;

  /**
   * The acceleration level (39), (41) on @p force_set (rigid constraints):
   * a_n, lambda_n of the set (0 for the other rigid ones; the compliant
   * ones' kept), and q*, v* in q_next, v_next. @p next_set (or nullptr) is
   * the set that position_level() will be asked for next, so that an
   * implementation may do part of it in the same pass.
   */
  virtual void acceleration_level(const std::vector<unsigned int>& force_set,
                                  const std::vector<unsigned int>* next_set) = 0;

  /**
   * The position and velocity level (40) on @p set, from q*, v* of the last
   * acceleration_level(): q_{n+1}, v_{n+1} and the gaps at t_{n+1} of every
   * constraint. Throws SimulationError if the multiplier system is singular.
   */
  virtual void position_level(const std::vector<unsigned int>& set) = 0;

  /// Ends the step (workspace that the step used is reset).
  virtual void finish_step() {}

protected:
  const SemiDiscreteSystem& system;
  double h;
  Step step;
};

/// The step system of @p system with step @p h, done by @p algebra.
std::unique_ptr<HalfExplicitStepSystem>
make_half_explicit_step_system(const SemiDiscreteSystem& system, double h,
                               LinearAlgebra algebra);

} // namespace pantocat
