#pragma once

#include <pantocat/base/contact_point_motion.h>
#include <pantocat/catenary/catenary_parameters.h>
#include <pantocat/space/smoothed_delta.h>

#include <optional>
#include <vector>

namespace pantocat
{
/**
 * The series solution of the classical moving-load problem on one span: a
 * string or a beam under tension (rho A w_tt - T w_xx + E I w_xxxx = F
 * delta_eps(x - x_p(t)), undamped, w = w_xx = 0 at both ends as in (3)),
 * starting undeformed and at rest, with x_p(t) = x_0 + v t below the wave
 * speed. With the modes sin(k_n x), k_n = n pi / L,
 *
 *   w(x, t) = sum_n q_n(t) sin(k_n x),
 *   q_n'' + omega_n^2 q_n = P_n sin(Omega_n t + theta_n),
 *   omega_n^2 = (T k_n^2 + E I k_n^4) / (rho A),  Omega_n = k_n v,  theta_n = k_n x_0,
 *   P_n = 2 F c_n / (rho A L),   c_n = int delta_eps(s) cos(k_n s) ds  (1 for a point
 * load),
 *
 * and from rest
 *   q_n = P_n / (omega_n^2 - Omega_n^2) [sin(Omega_n t + theta_n)
 *         - sin(theta_n) cos(omega_n t) - (Omega_n / omega_n) cos(theta_n) sin(omega_n
 * t)].
 *
 * The reference of the moving-force scenes: independent of any
 * grid, it checks FEM and FDM, the load row (33) and the time integrators.
 */
class MovingLoadSeries
{
public:
  /// @p delta: the smoothed load delta_eps, or none for a point load.
  MovingLoadSeries(const WireParameters& wire, double span, double force,
                   const ContactPointMotion& motion,
                   const std::optional<SmoothedDelta>& delta,
                   unsigned int n_modes = 1000);

  /// w(x, t) [m].
  double displacement(double x, double t) const;

  /// Lowest circular frequency omega_1 [1/s].
  double lowest_frequency() const { return omega.front(); }

private:
  double span;
  ContactPointMotion motion;
  std::vector<double> k, omega,
      amplitude; ///< k_n, omega_n, P_n / (omega_n^2 - Omega_n^2)
};
} // namespace pantocat
