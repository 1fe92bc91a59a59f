#pragma once

#include <array>
#include <cmath>

namespace pantocat
{
/**
 * The smoothed Dirac function delta_eps of Sec. 4.1, Eq. (25): the cubic C1
 * spline with knots -eps, 0, eps,
 *
 *   delta_eps(xi) = 1/eps - 3 xi^2/eps^3 + 2 |xi|^3/eps^4   for |xi| <= eps,
 *
 * and 0 outside. It is non-negative, has unit integral and delta_eps'(0) = 0.
 * Its second derivative jumps at the knots, so integrals of it against
 * piecewise polynomials are exact with Gauss rules only on pieces split at
 * the knots (see knots()).
 */
class SmoothedDelta
{
public:
  explicit SmoothedDelta(double epsilon);

  double epsilon() const { return eps; }

  /// k-th derivative (k = 0, 1, 2) of delta_eps at xi; 0 outside [-eps, eps].
  double derivative(double xi, unsigned int k) const;

  double value(double xi) const { return derivative(xi, 0); }

  /// Antiderivative Phi(xi) = int_{-inf}^{xi} delta_eps: 0 below -eps, 1 above eps.
  double integral_up_to(double xi) const;

  /**
   * int delta_eps(xi) (xi - d)_+ dxi: the load's lever beyond @p d, which
   * weights a kink of a piecewise linear height at distance d from the
   * load's centre (-d for d <= -eps, 0 for d >= eps).
   */
  double first_moment_beyond(double d) const;
  /// The knots -eps, 0, eps of the spline, relative to the centre.
  std::array<double, 3> knots() const { return {{-eps, 0., eps}}; }

private:
  double eps;
};

// Inline: the contact rows evaluate them at every control-volume edge under
// the load, at three time points per step (FdmCatenary::load_row).
inline double SmoothedDelta::derivative(const double xi, const unsigned int k) const
{
  const double a = std::abs(xi);
  if (a > eps)
    return 0.;
  const double sign = xi < 0. ? -1. : 1.;
  const double e3 = eps * eps * eps, e4 = e3 * eps;
  switch (k)
  {
  case 0:
    return 1. / eps - 3. * xi * xi / e3 + 2. * a * a * a / e4;
  case 1:
    return -6. * xi / e3 + 6. * sign * a * a / e4;
  case 2:
    return -6. / e3 + 12. * a / e4;
  default:
    return 0.;
  }
}

inline double SmoothedDelta::integral_up_to(const double xi) const
{
  if (xi <= -eps)
    return 0.;
  if (xi >= eps)
    return 1.;
  // The integral from 0 to |xi| of the even function, then symmetry.
  const double a = std::abs(xi);
  const double e3 = eps * eps * eps, e4 = e3 * eps;
  const double half = a / eps - a * a * a / e3 + 0.5 * a * a * a * a / e4;
  return xi < 0. ? 0.5 - half : 0.5 + half;
}
} // namespace pantocat
