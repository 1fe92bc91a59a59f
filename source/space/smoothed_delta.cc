#include <pantocat/space/smoothed_delta.h>

#include <cmath>

namespace pantocat
{
SmoothedDelta::SmoothedDelta(const double epsilon) : eps(epsilon) {}

double SmoothedDelta::derivative(const double xi, const unsigned int k) const
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

double SmoothedDelta::integral_up_to(const double xi) const
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
