#pragma once

#include <pantocat/base/contact_point_motion.h>

#include <deal.II/base/parameter_handler.h>

#include <array>
#include <optional>
#include <string>
#include <vector>

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
 * suspension and static force, the frame mass split into two bodies joined by
 * a stiff link), not the data of a particular pantograph.
 */
struct ThreeMassPantographParameters
{
  std::array<double, 3> masses = {{9.0, 8.0, 9.0}};            ///< m_1..m_3 [kg]
  std::array<double, 3> stiffnesses = {{7000.0, 20000.0, 0.}}; ///< c_1..c_3 [N/m]
  std::array<double, 3> dampings = {{30.0, 10.0, 130.0}};      ///< d_1..d_3 [N s/m]
  double uplift_force = 70.0;                                  ///< F_0 on body 3 [N]
};

/// What q = 0 of a mass chain means (MassChainPantograph).
enum class ChainReference
{
  /// Every spring at its unloaded length (the paper's (12)): the constant load is
  /// F_0 + F_a on the force body.
  relaxed_springs,
  /// The static equilibrium under F_0 with the head at z = 0 and pressed by
  /// lambda_p = F_0 (the S55 data sheet): the constant load is F_0 on the head and
  /// F_a on the force body.
  static_equilibrium
};

/// How a mass chain completes its consistent initial state (MassChainPantograph).
enum class ChainStart
{
  /// Bodies 1..n-1 in static balance under lambda_p(0) with the head on the wire.
  static_equilibrium,
  /// The paper's choice (13) for the first two bodies: w_p2 = w_p1 - offset, the
  /// velocity of body 2 from the head equation; bodies 3..n at rest in balance.
  offset
};

/**
 * Data of the mass-chain pantograph (MassChainPantograph): n bodies from the
 * head (body 1) to the frame (body n); spring k_i and damper c_i join body i
 * and body i + 1, k_n and c_n join the frame to the ground. The defaults are
 * the two-mass data of Sec. 2.2 (Fischer's parameters), so that a chain with
 * the defaults is the paper's pantograph (12).
 */
struct MassChainPantographParameters
{
  std::vector<double> masses = {9.0, 17.0};        ///< m_1..m_n [kg], head first
  std::vector<double> stiffnesses = {7000.0, 0.0}; ///< k_1..k_n [N/m]
  std::vector<double> dampings = {30.0, 130.0};    ///< c_1..c_n [N s/m]
  double static_force = 70.0;                      ///< F_0 [N]
  double aerodynamic_a = 0.;                       ///< a of F_a = a + b v^2 [N]
  double aerodynamic_b = 0.;                       ///< b of F_a = a + b v^2 [N s^2/m^2]
  int force_body = 0;                              ///< 1..n; 0 = the frame, body n
  ChainReference reference = ChainReference::relaxed_springs;
  ChainStart start = ChainStart::static_equilibrium;

  unsigned int n_bodies() const { return masses.size(); }
  /// The body (1..n) that carries F_0 + F_a.
  unsigned int uplift_body() const
  {
    return force_body == 0 ? n_bodies() : static_cast<unsigned int>(force_body);
  }
  /// F_a = a + b v^2 at speed @p speed [N].
  double aerodynamic_force(const double speed) const
  {
    return aerodynamic_a + aerodynamic_b * speed * speed;
  }
  /// Throws InputError naming @p subsection/<entry> for data no chain can have.
  void check(const std::string& subsection) const;
};

/// A speed in m/s from "88.9", "88.9 m/s" or "320 km/h"; none for other text.
std::optional<double> speed_from_text(const std::string& text);

/**
 * How the pantograph moves along the span and how it starts (Secs. 2.2 and 6):
 * x_p(t) = x_{p,0} + v_p t until x_p reaches the final position.
 */
struct PantographParameters
{
  double initial_position = 2.0; ///< x_{p,0} [m]
  double final_position = 18.0;  ///< x_p(t_e) [m]
  double speed = 32.0;           ///< v_p [m/s]
  double speed_ramp = 0.0; ///< T_r [s]: from rest to v_p (ContactPointMotion); 0: none
  double initial_contact_force = 8.75; ///< lambda_p(0) [N]
  double initial_offset = 0.0;         ///< w_{p,1}(0) - w_{p,2}(0) [m], (13) and Sec. 6
  TwoMassPantographParameters two_mass;
  ThreeMassPantographParameters three_mass;
  MassChainPantographParameters mass_chain;

  /// The motion x_p(t), with the speed ramp if any.
  ContactPointMotion motion() const { return {initial_position, speed, speed_ramp}; }
  /// x_p(t).
  double position(double t) const { return motion().position(t); }
  /// The time t_e with x_p(t_e) = final position (ContactPointMotion::time_at():
  /// with a ramp T_r / 2 later than at v_p throughout, or inside the ramp if the
  /// run is shorter than the v_p T_r / 2 it takes).
  double end_time() const { return motion().time_at(final_position); }

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
