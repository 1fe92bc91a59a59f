#pragma once

#include <pantocat/pantograph/pantograph_model.h>
#include <pantocat/pantograph/pantograph_parameters.h>

namespace pantocat
{
/**
 * A pantograph of n lumped bodies in a chain, head (body 1) to frame (body n):
 * spring k_i and damper c_i between body i and body i + 1, k_n and c_n between
 * the frame and the ground, the static force F_0 and the aerodynamic force
 * F_a = a + b v_p^2 on the force body j (default the frame):
 *
 *   m_1 w_1'' = -k_1 (w_1 - w_2) - c_1 (w_1' - w_2') + f_1 - lambda_p,
 *   m_i w_i'' =  k_{i-1} (w_{i-1} - w_i) + c_{i-1} (w_{i-1}' - w_i')
 *              - k_i (w_i - w_{i+1}) - c_i (w_i' - w_{i+1}') + f_i,
 *   m_n w_n'' =  k_{n-1} (w_{n-1} - w_n) + c_{n-1} (...) - k_n w_n - c_n w_n' + f_n,
 *
 * the form (10) with tridiagonal K and D, diagonal M, and b = w_1, B = e_1 as
 * in (11); the contact (32) and the coupling are those of the two-mass model
 * (12), which is the chain with n = 2 and the same data. The constant load f
 * depends on the reference state:
 *
 *  - relaxed springs (the paper's (12)): f = (F_0 + F_a) e_j;
 *  - static equilibrium (the S55 data sheet): the coordinates are displacements
 *    from the static state x* under F_0 with the head at z = 0 pressed by
 *    lambda_p = F_0, K x* = F_0 (e_j - e_1). With w = x - x* the load
 *    F_0 e_j + F_a e_j - K x* is f = F_0 e_1 + F_a e_j: F_0 reaches the head
 *    through the preloaded springs, and at rest on a wire at z = 0 with
 *    lambda_p = F_0, q = 0 solves (10) exactly. The quasi-static contact force
 *    is F_0 + F_a - k_n w_n.
 *
 * No gravity acts on the pantograph: F_0 is the net static force, as in (12).
 */
class MassChainPantograph : public PantographModel
{
public:
  /// The chain @p parameters running at @p speed (for F_a = a + b v_p^2).
  MassChainPantograph(const MassChainPantographParameters& parameters, double speed);

  std::string name() const override { return "mass-chain"; }
  unsigned int n_dofs() const override { return p.n_bodies(); }
  /// w_p1 (head), ..., w_pn (frame), as the two- and three-mass models.
  std::vector<std::string> coordinate_names() const override;
  void assemble(BlockOperator& op) const override;
  SparseRow head_row() const override;
  /// F_0 + F_a [N]: the quasi-static contact force with the frame at rest at 0.
  double static_force() const override;

  /**
   * The head at @p head_position with @p head_velocity and @p head_acceleration,
   * pressed by @p contact_force (lambda_p(0)), so that the head equation of (10)
   * holds (the state is consistent with (32) on position, velocity and
   * acceleration level, Sec. 2.2).
   *
   * Start static equilibrium: every body moves with the head; link i carries
   * the force T_i that holds body i in balance (T_1 = m_1 a_1 - f_1 + lambda_p,
   * T_i = T_{i-1} - f_i), by its spring, w_{i+1} = w_i + T_i / k_i, or, if
   * k_i = 0, by its damper, w_{i+1}' = w_i' + T_i / c_i. Bodies 2..n-1 are then at
   * rest relative to the head; the frame is too exactly when lambda_p(0) is the
   * quasi-static force of the frame's position, otherwise it starts with the
   * ground link's imbalance as acceleration. @p offset is not used.
   *
   * Start offset, the paper's (13) as for the two- and three-mass models:
   * w_2 = w_1 - offset, w_2' from the head equation; bodies 3..n at rest at
   * the balance of their own forces given w_2.
   */
  void consistent_state(double head_position, double head_velocity,
                        double head_acceleration, double contact_force, double offset,
                        dealii::Vector<double>& q,
                        dealii::Vector<double>& v) const override;

  /// The constant load f of (10), by the reference state (see the class).
  dealii::Vector<double> constant_load() const;

private:
  MassChainPantographParameters p;
  double aerodynamic_force;
};
} // namespace pantocat
