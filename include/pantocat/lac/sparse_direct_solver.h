#pragma once

#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <string>
#include <vector>

namespace pantocat
{
/**
 * A factorised sparse matrix: factorise once, solve many times. The implicit
 * integrators use it for their constant iteration matrices.
 *
 * The semi-discrete matrices are banded within each body (half bandwidth 1
 * to 3, no coupling between bodies), and symmetric positive definite. Such a
 * matrix is factorised by LAPACK's banded Cholesky (dpbtrf) and solved by a
 * forward and a backward substitution on the band (about four times faster
 * than UMFPACK at 1500 unknowns, doc/benchmarks.md; the substitution is
 * written out because the reference BLAS behind dpbtrs is slower still).
 * Any other matrix goes to deal.II's UMFPACK.
 */
class SparseDirectSolver
{
public:
  /// Factorises @p matrix; throws SimulationError naming @p what if it is singular.
  void factorize(const dealii::SparseMatrix<double>& matrix, const std::string& what);
  /// x <- A^{-1} x
  void solve(dealii::Vector<double>& x) const;
  /// True if the banded Cholesky path is used.
  bool is_banded() const { return banded; }

private:
  bool try_banded_cholesky(const dealii::SparseMatrix<double>& matrix);

  bool banded = false;
  int n = 0, kd = 0;
  std::vector<double> band;       ///< LAPACK upper band storage of the Cholesky factor U
  std::vector<double> reciprocal; ///< 1 / U(i, i)
  dealii::SparseDirectUMFPACK umfpack;
};
} // namespace pantocat
