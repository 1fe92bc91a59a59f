#pragma once

#include <deal.II/lac/vector.h>

#include <cstddef>

namespace pantocat
{
/**
 * The number of entries with !(|x_i| <= @p bound): not finite, or beyond
 * @p bound. The every-step test of the run's bound guard, so written for the
 * vector unit; the count is exact (no floating-point arithmetic).
 */
std::size_t count_outside(const dealii::Vector<double>& x, double bound);

/// max |x_i|, or a non-finite value if an entry is not finite (one pass).
double largest_magnitude(const dealii::Vector<double>& x);
} // namespace pantocat
