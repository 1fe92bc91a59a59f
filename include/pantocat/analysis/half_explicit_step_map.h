#pragma once

#include <pantocat/system/semi_discrete_system.h>

#include <deal.II/lac/vector.h>

#include <memory>
#include <vector>

namespace pantocat
{
/**
 * The linear part of one step t_n -> t_{n+1} of the half-explicit method
 * (39)-(41) with a fixed set of constraints, as a map on the state
 * x_n = (q_n, v_n, v_{n-1}):
 *
 *   (M + dt/2 D) a = -K q_n - D (v_{n-1} + v_n)/2 + G_C^T lambda_C + G_A^T lambda,
 *   lambda_C = -k G_C q_n - c (G_{t,C} q_n + G_C (v_{n-1} + v_n)/2)  (engaged springs),
 *   G_A a + 2 G_{t,A} v_n + G_{tt,A} q_n = 0                        (rigid, at t_n),
 *   v* = v_{n-1} + 2 dt a,  q* = q_n + dt (v_n + v*)/2,
 *   q_{n+1} = q* + M^-1 (dt^2 G(t_n)^T + dt G_t(t_{n+1/2})^T) eta + dt M^-1
 * G(t_{n+1/2})^T mu, v_{n+1} = v* + 2 dt M^-1 G(t_n)^T eta, G(t_{n+1}) q_{n+1} = 0,
 * G_t(t_{n+1}) q_{n+1} + G(t_{n+1}) v_{n+1} = 0,
 *
 * the same formulas as HalfExplicitIntegrator, re-implemented here without
 * the loads and offsets (f, z and their derivatives): the difference of two
 * runs with the same constraints active evolves by exactly this map, so its
 * growth is that of a perturbation of the run. The rows of each constraint
 * are evaluated at three times given per step: (t_n, t_n + dt/2, t_n + dt)
 * for the moving contact as it runs, or one time for a frozen one.
 */
class HalfExplicitStepMap
{
public:
  /// The state (q_n, v_n, v_{n-1}).
  struct State
  {
    dealii::Vector<double> q, v, v_prev;
  };

  /**
   * @p active: the rigid constraints taken as active and the compliant ones
   * taken as engaged (DynamicState::active of a state of the run); the others
   * are left out.
   */
  HalfExplicitStepMap(const SemiDiscreteSystem& system, const std::vector<bool>& active,
                      double dt);
  ~HalfExplicitStepMap();

  /// x <- the step with the rows at @p t_n, @p t_half and @p t_next.
  void apply(double t_n, double t_half, double t_next, State& x);

  double time_step() const { return dt; }
  unsigned int n_dofs() const { return system.n_dofs(); }

private:
  /// The inverse of M + c D, block by block (diagonal blocks by division).
  class BlockInverse;
  struct Forces;
  struct Rows;
  struct CompactColumn;

  void evaluate_rows(double t_n, double t_half, double t_next);
  /// @p out = the column inverse^-1 row^T on its support (CompactColumn).
  void column(const BlockInverse& inverse, const SparseRow& row,
              CompactColumn& out) const;

  const SemiDiscreteSystem& system;
  double dt;
  std::vector<unsigned int> rigid, springs;
  std::unique_ptr<BlockInverse> mass_inverse, smoothed_inverse;
  std::unique_ptr<Forces> forces;
  std::unique_ptr<Rows> rows;
  dealii::Vector<double> a, q_new, v_new;
};

/// How the contact's rows enter the estimate of growth_per_step().
enum class ContactRows
{
  moving, ///< as in the run: the steps from t_0, the rows at t_n, t_{n+1/2}, t_{n+1}
  frozen  ///< one step repeated, all rows (with G_t, G_tt) at one time t_0
};

/**
 * The growth per step of perturbations of the half-explicit method: exp of
 * the slope of the least-squares line through log |x_k|, k = N/2 ... N, for
 * x_0 random (fixed seed) and N = @p steps steps
 * of HalfExplicitStepMap from @p t0 (ContactRows::moving) or of the one map at
 * @p t0 (ContactRows::frozen), with |x|^2 = (2/dt)^2 |q|^2 + |v|^2 + |v_prev|^2.
 * For the frozen map this is the power iteration for its spectral radius; for
 * the moving one that of the product of the maps over the steps (for a
 * contact that crosses cells of one length, its Floquet multiplier per step).
 * About 1 (a little less with damping) where the method is stable.
 */
double growth_per_step(const SemiDiscreteSystem& system, const std::vector<bool>& active,
                       double dt, double t0, unsigned int steps,
                       ContactRows contact = ContactRows::moving);
} // namespace pantocat
