#pragma once

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <functional>
#include <vector>

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

/**
 * Solves the bordered multiplier system [A B; C D] [x; y] = [r; s] by block
 * elimination: A is the (sparse, factorised once per active set) block of the
 * constraints with constant rows, the border B, C, D that of the p moving
 * ones (the contacts), with A^-1 applied in place by @p solve_fixed:
 * x0 = A^-1 r, Z = A^-1 B, (D - C Z) y = s - C x0, x = x0 - Z y. @p B holds
 * the columns of B (becomes Z), @p C the rows of C; on return @p r holds x
 * and @p s holds y. Costs p + 1 applications of A^-1 (none for a zero border
 * column), side by side in batches (FixedConstraintSchur), and a dense
 * p x p solve. (The half-explicit method keeps its own allocation-free
 * single-solve version.)
 */
void solve_bordered_batched(
    const std::function<void(const std::vector<dealii::Vector<double>*>&)>& solve_fixed,
    std::vector<dealii::Vector<double>>& B, const std::vector<dealii::Vector<double>>& C,
    dealii::FullMatrix<double>& D, dealii::Vector<double>& r, dealii::Vector<double>& s,
    double t, const char* what);
} // namespace pantocat
