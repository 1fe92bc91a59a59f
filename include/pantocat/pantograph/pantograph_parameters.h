#pragma once

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace pantocat
{
/// Data of the two-mass pantograph (12) (Fischer's parameters, Sec. 2.2).
struct TwoMassPantographParameters
{
  double head_mass = 9.0;         ///< m_1 [kg]
  double frame_mass = 17.0;       ///< m_2 [kg]
  double head_stiffness = 7000.0; ///< c_1 [N/m]
  double frame_stiffness = 0.0;   ///< c_2 [N/m]
  double head_damping = 30.0;     ///< d_1 [N s/m]
  double frame_damping = 130.0;   ///< d_2 [N s/m]
  double uplift_force = 70.0;     ///< F_0 [N]
};

/**
 * How the pantograph moves along the span and how it starts (Secs. 2.2 and 6):
 * x_p(t) = x_{p,0} + v_p t until x_p reaches the final position.
 */
struct PantographParameters
{
  std::string model = "two-mass";
  double initial_position = 2.0;       ///< x_{p,0} [m]
  double final_position = 18.0;        ///< x_p(t_e) [m]
  double speed = 32.0;                 ///< v_p [m/s]
  double initial_contact_force = 8.75; ///< lambda_p(0) [N]
  double initial_offset = 0.0;         ///< w_{p,1}(0) - w_{p,2}(0) [m], (13) and Sec. 6
  /// Droppers and contact as equations (4), (32) instead of the inequalities of Sec. 5.3.
  bool bilateral_constraints = false;
  TwoMassPantographParameters two_mass;

  /// x_p(t).
  double position(double t) const { return initial_position + speed * t; }
  /// End time t_e with x_p(t_e) = final position.
  double end_time() const { return (final_position - initial_position) / speed; }

  static void declare_parameters(dealii::ParameterHandler& prm);
  void parse_parameters(dealii::ParameterHandler& prm);
  /// Checks against the span and the load half-width; throws InputError.
  void check(double span, double load_half_width) const;
};
} // namespace pantocat
