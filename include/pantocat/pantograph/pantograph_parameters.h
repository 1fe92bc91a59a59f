#pragma once

#include <deal.II/base/parameter_handler.h>

#include <array>
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
 * Data of the three-mass pantograph (ThreeMassPantograph): head, upper and
 * lower frame. The defaults are illustrative (the two-mass model's head
 * suspension and uplift force, the frame mass split into two bodies joined by
 * a stiff link), not the data of a particular pantograph.
 */
struct ThreeMassPantographParameters
{
  std::array<double, 3> masses = {{9.0, 8.0, 9.0}};            ///< m_1..m_3 [kg]
  std::array<double, 3> stiffnesses = {{7000.0, 20000.0, 0.}}; ///< c_1..c_3 [N/m]
  std::array<double, 3> dampings = {{30.0, 10.0, 130.0}};      ///< d_1..d_3 [N s/m]
  double uplift_force = 70.0;                                  ///< F_0 on body 3 [N]
};

/**
 * How the pantograph moves along the span and how it starts (Secs. 2.2 and 6):
 * x_p(t) = x_{p,0} + v_p t until x_p reaches the final position.
 */
struct PantographParameters
{
  double initial_position = 2.0;       ///< x_{p,0} [m]
  double final_position = 18.0;        ///< x_p(t_e) [m]
  double speed = 32.0;                 ///< v_p [m/s]
  double initial_contact_force = 8.75; ///< lambda_p(0) [N]
  double initial_offset = 0.0;         ///< w_{p,1}(0) - w_{p,2}(0) [m], (13) and Sec. 6
  TwoMassPantographParameters two_mass;
  ThreeMassPantographParameters three_mass;

  /// x_p(t).
  double position(double t) const { return initial_position + speed * t; }
  /// End time t_e with x_p(t_e) = final position.
  double end_time() const { return (final_position - initial_position) / speed; }

  /// The prm subsection these were read from ("Pantograph", "Pantograph 2", ...).
  std::string subsection = "Pantograph";

  /// Declares subsection @p subsection with @p defaults as the default values.
  static void declare_parameters(dealii::ParameterHandler& prm,
                                 const std::string& subsection,
                                 const PantographParameters& defaults);
  /// Declares subsection Pantograph with the benchmark's defaults (Sec. 2.2).
  static void declare_parameters(dealii::ParameterHandler& prm);
  void parse_parameters(dealii::ParameterHandler& prm,
                        const std::string& subsection = "Pantograph");
  /// Checks against the span and the load half-width; throws InputError.
  void check(double span, double load_half_width) const;
};
} // namespace pantocat
