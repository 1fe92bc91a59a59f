#pragma once

#include <pantocat/pantograph/pantograph_parameters.h>

#include <cmath>

namespace pantocat
{
/**
 * The two-mass pantograph (12) with its head held on a rigid wire at height 0
 * (bilateral contact): the frame obeys m_2 y'' + (d_1 + d_2) y' + (c_1 + c_2) y = 0,
 * y = w_p2 - F_0 / (c_1 + c_2), starting from the consistent state of
 * @p p (initial offset and contact force, the frame velocity from the head
 * equation), and the contact force is lambda_p = c_1 w_p2 + d_1 w_p2'.
 * Returns lambda_p(t) in closed form.
 */
inline double rigid_wire_contact_force(const PantographParameters& p, const double t)
{
  const auto& m = p.two_mass;
  const double c = m.head_stiffness + m.frame_stiffness;
  const double sigma = (m.head_damping + m.frame_damping) / (2. * m.frame_mass);
  const double omega_d = std::sqrt(c / m.frame_mass - sigma * sigma);
  const double y0 = -p.initial_offset - m.uplift_force / c; // w_p1(0) = 0
  const double v0 =
      (p.initial_contact_force + m.head_stiffness * p.initial_offset) / m.head_damping;
  const double B = (v0 + sigma * y0) / omega_d;
  const double e = std::exp(-sigma * t);
  const double y = e * (y0 * std::cos(omega_d * t) + B * std::sin(omega_d * t));
  const double dy =
      -sigma * y +
      e * omega_d * (-y0 * std::sin(omega_d * t) + B * std::cos(omega_d * t));
  return m.head_stiffness * (y + m.uplift_force / c) + m.head_damping * dy;
}
} // namespace pantocat
