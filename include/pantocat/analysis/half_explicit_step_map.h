#pragma once

#include <pantocat/system/semi_discrete_system.h>

#include <deal.II/lac/vector.h>

#include <memory>
#include <vector>

namespace pantocat
{
class HalfExplicitIntegrator;

/// How the contact's rows enter HalfExplicitStepMap and growth_per_step().
enum class ContactRows
{
  moving, ///< as in the run: the steps from t_0, the rows at t_n, t_{n+1/2}, t_{n+1}
  frozen  ///< one step repeated, all rows (with G_t, G_tt) at one time t_0
};

/**
 * The linear part of one step t_n -> t_{n+1} of the half-explicit method
 * (39)-(41) with a fixed set of constraints, as a map on the state
 * x_n = (q_n, v_n, v_{n-1}): the method itself (HalfExplicitIntegrator) on
 * the homogeneous view of the system, i.e. the same M, D, K without the
 * loads, and the constraints of @p active without their offsets z, z_t, z_tt
 * (homogeneous_view()). The difference of two runs with the same
 * constraints active evolves by exactly this map, so its growth is that of
 * a perturbation of the run.
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
   * are left out. With ContactRows::frozen the moving rows are those at
   * @p t0 at every step.
   */
  HalfExplicitStepMap(const SemiDiscreteSystem& system, const std::vector<bool>& active,
                      double dt, ContactRows contact = ContactRows::moving,
                      double t0 = 0.);
  ~HalfExplicitStepMap();

  /// x <- the step from t_n = @p t_n.
  void apply(double t_n, State& x);

  double time_step() const { return dt; }
  unsigned int n_dofs() const { return view->n_dofs(); }

private:
  double dt;
  std::unique_ptr<SemiDiscreteSystem> view;
  std::unique_ptr<HalfExplicitIntegrator> method;
};

/**
 * The homogeneous view of @p system: a system with the same M, D, K, no
 * load, and for each constraint of @p active (a rigid one active, a
 * compliant one engaged) a bilateral one with the same rows G, G_t, G_tt and
 * compliance but z = z_t = z_tt = 0, its rows evaluated at @p frozen_time
 * whatever the time asked for if @p freeze. The view refers to @p system's
 * constraints, which must outlive it.
 */
std::unique_ptr<SemiDiscreteSystem> homogeneous_view(const SemiDiscreteSystem& system,
                                                     const std::vector<bool>& active,
                                                     bool freeze = false,
                                                     double frozen_time = 0.);

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
