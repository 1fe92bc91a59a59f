#pragma once

#include <deal.II/base/parameter_handler.h>

#include <vector>

namespace pantocat
{
/// Physical data of one wire of the catenary, Eq. (2).
struct WireParameters
{
  double mass_per_length = 0.;   ///< rho A [kg/m]
  double tension = 0.;           ///< T [N]
  double bending_stiffness = 0.; ///< E I [N m^2]; 0 for the string (carrier)
  double damping = 0.;           ///< beta [N s/m^2]

  /// Wave speed sqrt(T / rho A) [m/s].
  double wave_speed() const;
};

/**
 * The reduced catenary of Sec. 2.2 / Fig. 4: a carrier (string) and a contact
 * wire (Euler-Bernoulli beam) over one span, connected by droppers (Eqs. (2)-(6)).
 * The defaults are the benchmark data of the paper (catenary Re 250).
 */
struct CatenaryParameters
{
  double span = 20.0;          ///< L [m]: the length of the span (Catenary/Span)
  double support_height = 1.0; ///< l_c: carrier height at x = 0 and x = L [m], Eq. (3)
  double gravity = 9.81;       ///< g [m/s^2]
  WireParameters carrier = {0.6, 15000., 0., 0.03};
  WireParameters contact_wire = {1.068, 15000., 150., 0.03};

  std::vector<double> dropper_positions = {5.5, 14.5}; ///< x_{d,j} [m]
  std::vector<double> dropper_lengths = {0.95, 0.95};  ///< l_j [m]
  double dropper_mass_per_length = 0.14;               ///< rho_d A_d [kg/m]
  double clamp_mass = 0.25;                            ///< m_s [kg]

  unsigned int n_droppers() const { return dropper_positions.size(); }

  /**
   * The wires' domain is [0, length()]: the spans of the catenary end to end
   * (one span in the paper's reduced model). Grids, positions and bounds
   * refer to the domain; span lengths only to the geometry along it.
   */
  double length() const { return span; }
  /// Positions of the supports along the domain: the ends of every span.
  std::vector<double> support_positions() const { return {0., span}; }

  /// Gravity load of clamps and half a dropper at dropper j, (m_s + l_j rho_d A_d / 2) g,
  /// Eq. (4).
  double clamp_load(unsigned int j) const;

  static void declare_parameters(dealii::ParameterHandler& prm);
  void parse_parameters(dealii::ParameterHandler& prm);
  /// Cross-checks; throws InputError naming the parameter.
  void check() const;
};
} // namespace pantocat
