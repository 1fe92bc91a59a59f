#pragma once

#include <array>

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

  /// The knots -eps, 0, eps of the spline, relative to the centre.
  std::array<double, 3> knots() const { return {{-eps, 0., eps}}; }

private:
  double eps;
};
} // namespace pantocat
