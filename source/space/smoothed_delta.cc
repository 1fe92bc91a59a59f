#include <pantocat/space/smoothed_delta.h>

#include <algorithm>
#include <utility>

namespace pantocat
{
SmoothedDelta::SmoothedDelta(const double epsilon) : eps(epsilon) {}

double SmoothedDelta::first_moment_beyond(const double d) const
{
  if (d >= eps)
    return 0.;
  if (d <= -eps)
    return -d; // delta_eps has unit integral and first moment 0
  // delta_eps (xi - d) is a quartic on each piece of [d, eps] split at 0: the
  // 3-point Gauss rule integrates it exactly.
  constexpr double node = 0.7745966692414834, w_outer = 5. / 9., w_centre = 8. / 9.;
  double sum = 0.;
  for (const auto& [a, b] :
       {std::pair{d, std::max(d, 0.)}, std::pair{std::max(d, 0.), eps}})
  {
    if (b <= a)
      continue;
    const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
    for (const auto& [t, w] :
         {std::pair{-node, w_outer}, std::pair{0., w_centre}, std::pair{node, w_outer}})
    {
      const double xi = mid + half * t;
      sum += w * half * value(xi) * (xi - d);
    }
  }
  return sum;
}
} // namespace pantocat
