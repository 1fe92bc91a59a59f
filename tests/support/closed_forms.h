#pragma once

#include <algorithm>
#include <cmath>

namespace pantocat
{
/**
 * Tensioned simply supported beam under a point load, EI w'''' - T w'' = P
 * delta(x - a) on (0, L), w = w'' = 0 at both ends (upward P > 0 lifts it):
 * w = -M/T + v with M = P((x-a)_+ - x(L-a)/L) and
 * v = -(P/T) sinh(k x<) sinh(k(L - x>)) / (k sinh(kL)), k^2 = T/EI,
 * the sinh products evaluated without overflow (kL may be large).
 */
inline double beam_point_load(const double x, const double a, const double P,
                              const double L, const double T, const double EI)
{
  const double k = std::sqrt(T / EI);
  const double M = P * (std::max(0., x - a) - x * (L - a) / L);
  const double lo = std::min(x, a), hi = std::max(x, a);
  // sinh(k lo) sinh(k (L - hi)) / sinh(k L), evaluated without overflow.
  const double ratio = 0.5 * (std::exp(k * (lo - hi)) - std::exp(-k * (lo + hi))) *
                       (1. - std::exp(-2. * k * (L - hi))) / (1. - std::exp(-2. * k * L));
  return -M / T - P / T * ratio / k;
}
} // namespace pantocat
