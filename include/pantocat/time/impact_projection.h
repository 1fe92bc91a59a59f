#pragma once

#include <pantocat/constrained/constrained_operator.h>
#include <pantocat/system/semi_discrete_system.h>

#include <deal.II/lac/vector.h>

#include <memory>
#include <vector>

namespace pantocat
{
/**
 * The inelastic impact (restitution 0) of Sec. 5.3 at one time point, as an
 * event-driven integrator does it at a located event: with the constraints
 * @p holding that hold after the impact (those that closed and those that
 * held before),
 *
 *   q <- q + M^-1 G^T mu,  G_i q + z_i = 0            (positions onto g = 0),
 *   v <- v + M^-1 G^T P,   G_t,i q + G_i v + z_t,i = 0 (velocities onto dg/dt = 0),
 *
 * for i in holding, G and G_t at t. P [N s] is the impulse of each holding
 * constraint: the momentum M (v+ - v-) = G^T P that stops the approach. The
 * fixed-step integrators take the step t_n -> t_{n+1} without a constraint
 * that closes in it (ActiveSetIteration::ClosingConstraint::after_step) and
 * project at t_{n+1}, so the impact is located to within one step and the
 * step's own multipliers never carry the impact (a force of order 1/dt).
 *
 * The projections are multiplier systems of the operator M
 * (ConstrainedOperator::project()).
 */
class ImpactProjection
{
public:
  /// With the operator @p mass = M (kept by reference).
  ImpactProjection(const SemiDiscreteSystem& system, ConstrainedOperator& mass);

  /// What an impact did.
  struct Result
  {
    /// P per constraint [N s], 0 for the others; P_i + dt lambda_i >= 0 for a
    /// unilateral one (a share of a neighbour's impact may be negative while
    /// its force over the step is larger).
    std::vector<double> impulse;
    std::vector<unsigned int> separated; ///< unilateral ones of holding that separate
  };

  /**
   * Projects @p q and @p v at time @p t (constraint rows @p rows at t) onto
   * the constraints @p holding (rigid ones). On velocity level the impact law
   * is complementary over the step of length @p dt, in which the holding
   * constraints carry the forces @p lambda (0 for the closing ones): the
   * momentum P_i + dt lambda_i that a unilateral constraint transfers in the
   * step is >= 0, and dg_i/dt >= 0 after; one of them is 0 (Moreau's
   * velocity-level law for a time step). A constraint whose momentum would
   * pull (the others' impulses move it apart faster than its force closes it
   * within the step) is taken out of the velocity projection and separates;
   * the projection is repeated without it (a principal pivoting on the few
   * constraints of the impact). It keeps g = 0 at t and is reported in
   * Result::separated, to be set inactive by the integrator.
   *
   * Measured why the step's force counts: at 56 m/s, dropper 2 re-tensions
   * 0.2 m from the contact, whose force is 150 N. With P_i >= 0 alone the
   * contact separates at 0.013 m/s, and the 150 N on the 0.28 kg of wire
   * under it close it again within one step: a cascade of one-step
   * intervals (17 contact losses where IDA, which locates them, sees 3).
   * With P_i + dt lambda_i >= 0 the contact holds (its share -0.0039 N s
   * against 150 N x 5e-5 s), as in IDA.
   */
  Result project(const std::vector<ConstraintState>& rows,
                 const std::vector<unsigned int>& holding, double t,
                 const std::vector<double>& lambda, double dt, dealii::Vector<double>& q,
                 dealii::Vector<double>& v);

private:
  /// x <- x + M^-1 G^T y with residual_i + G_i M^-1 G^T y = 0 on @p holding; y.
  template <typename Residual>
  std::vector<double> project_level(const std::vector<ConstraintState>& rows,
                                    const std::vector<unsigned int>& holding, double t,
                                    Residual residual, dealii::Vector<double>& x);

  const SemiDiscreteSystem& system;
  ConstrainedOperator& mass;
};
} // namespace pantocat
