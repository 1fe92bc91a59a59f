#pragma once

#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <string>

namespace pantocat
{
/**
 * A factorised sparse matrix: factorise once, solve many times. The implicit
 * integrators use it for the constant iteration matrices; the factorisation
 * is deal.II's UMFPACK.
 */
class SparseDirectSolver
{
public:
  /// Factorises @p matrix; throws SimulationError naming @p what if it is singular.
  void factorize(const dealii::SparseMatrix<double>& matrix, const std::string& what);
  /// x <- A^{-1} x
  void solve(dealii::Vector<double>& x) const;
  unsigned long n_solves() const { return solves; }

private:
  dealii::SparseDirectUMFPACK umfpack;
  mutable unsigned long solves = 0;
};
} // namespace pantocat
