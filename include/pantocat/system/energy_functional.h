#pragma once

#include <pantocat/system/semi_discrete_system.h>

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <vector>

namespace pantocat
{
/**
 * x^T A x of a square sparse matrix in compact form: the diagonal, and each
 * pair (i, j > i) once with the weight a_ij + a_ji (the form sees only the
 * symmetric part of A), entries that are zero dropped. A mass matrix that
 * shares the stiffness's sparsity pattern but is lumped (FDM) keeps only
 * its diagonal; a symmetric one keeps half of its off-diagonal entries.
 */
class QuadraticForm
{
public:
  explicit QuadraticForm(const dealii::SparseMatrix<double>& A);
  double operator()(const dealii::Vector<double>& x) const;

private:
  std::vector<double> diagonal;
  std::vector<unsigned int> row_start, column; ///< the pairs j > i by row i
  std::vector<double> weight;
};

/**
 * The energy E(q, v, t) of SemiDiscreteSystem::energy, for evaluation again
 * and again on one system (the energy guard, RunGuard): v^T M v / 2 and
 * q^T K q / 2 as compact quadratic forms. On the paper's FDM grid (N+1 = 500)
 * an evaluation costs a third of the two sparse-matrix passes of
 * SemiDiscreteSystem::energy. The same value up to round-off (the
 * sums run in another order).
 */
class EnergyFunctional
{
public:
  explicit EnergyFunctional(const SemiDiscreteSystem& system);
  double operator()(const dealii::Vector<double>& q, const dealii::Vector<double>& v,
                    double t) const;

private:
  const SemiDiscreteSystem& system;
  QuadraticForm mass, stiffness;
};
} // namespace pantocat
