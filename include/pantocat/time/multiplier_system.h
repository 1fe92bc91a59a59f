#pragma once

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

namespace pantocat
{
/**
 * Solves the small dense system of the multipliers (lambda, eta, mu) of the
 * active constraints: x = A^{-1} b, A overwritten. Throws SimulationError
 * naming time @p t and @p what if A is singular (linearly dependent active
 * constraints). Does nothing for an empty active set.
 */
void solve_multiplier_system(dealii::FullMatrix<double>& A,
                             const dealii::Vector<double>& b, dealii::Vector<double>& x,
                             double t, const char* what);
} // namespace pantocat
