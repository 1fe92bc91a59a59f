#pragma once

#include <deal.II/lac/sparse_matrix.h>

namespace pantocat
{
/// Half bandwidth max |i - j| over the non-zeros of @p matrix.
unsigned int half_bandwidth(const dealii::SparseMatrix<double>& matrix);

/**
 * The largest eigenvalue of the symmetric-definite pencil A x = lambda B x
 * (A symmetric, B symmetric positive definite), both banded: the smallest
 * sigma for which sigma B - A is positive definite (Sylvester's law of
 * inertia), found by bisection down to neighbouring doubles with one banded
 * Cholesky factorisation (LAPACK dpbtrf) per trial. O(n b^2) per trial, about
 * 55 trials: linear in n, where a reduction to tridiagonal form (dsbgvx) costs
 * O(n^2 b). Returned from above: sigma B - A is positive definite in floating
 * point at the value returned, and not at the double below it, to round-off of
 * the factorisation (relative 1e-15 to 1e-13 for the wires' pencils).
 */
double largest_generalized_eigenvalue(const dealii::SparseMatrix<double>& A,
                                      const dealii::SparseMatrix<double>& B);

/**
 * The smallest eigenvalue of A x = lambda B x for A and B both symmetric
 * positive definite, computed as 1 / (largest eigenvalue of B x = mu A x): a
 * largest eigenvalue is computed to full relative accuracy, a smallest one of
 * an ill-conditioned pencil would not be. By LAPACK's dsbgvx (a reduction to
 * tridiagonal form, O(n^2 b)): the bisection of
 * largest_generalized_eigenvalue() resolves mu only to round-off times the
 * condition of A (3e-10 relative for the contact wire of Table 1).
 */
double smallest_generalized_eigenvalue(const dealii::SparseMatrix<double>& A,
                                       const dealii::SparseMatrix<double>& B);
} // namespace pantocat
