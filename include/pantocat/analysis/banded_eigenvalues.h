#pragma once

#include <deal.II/lac/sparse_matrix.h>

namespace pantocat
{
/// Half bandwidth max |i - j| over the non-zeros of @p matrix.
unsigned int half_bandwidth(const dealii::SparseMatrix<double>& matrix);

/**
 * The largest eigenvalue of the symmetric-definite pencil A x = lambda B x
 * (A symmetric, B symmetric positive definite), both banded, by LAPACK's
 * dsbgvx on band storage: O(n b^2) memory and no dense n x n matrix.
 */
double largest_generalized_eigenvalue(const dealii::SparseMatrix<double>& A,
                                      const dealii::SparseMatrix<double>& B);

/**
 * The smallest eigenvalue of A x = lambda B x for A and B both symmetric
 * positive definite, computed as 1 / (largest eigenvalue of B x = mu A x): a
 * largest eigenvalue is computed to full relative accuracy, a smallest one of
 * an ill-conditioned pencil would not be.
 */
double smallest_generalized_eigenvalue(const dealii::SparseMatrix<double>& A,
                                       const dealii::SparseMatrix<double>& B);
} // namespace pantocat
