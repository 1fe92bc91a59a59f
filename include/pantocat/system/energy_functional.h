#pragma once

#include <pantocat/system/semi_discrete_system.h>

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <vector>

namespace pantocat
{
/**
 * x^T A x of a square sparse matrix: the diagonal, and each pair (i, j > i)
 * once with the weight a_ij + a_ji (the form sees only the symmetric part of
 * A), entries that are zero dropped. A mass matrix that shares the
 * stiffness's sparsity pattern but is lumped (FDM) keeps only its diagonal; a
 * symmetric one keeps half of its off-diagonal entries.
 *
 * The pairs are stored by their offset j - i, one weight vector per offset
 * (a band: contiguous products that the vector unit takes four at a time),
 * when at least half of the band's places hold a pair and there are at most
 * 16 offsets (the FDM and FEM wires, numbered along each wire); otherwise
 * row by row (compact rows: the pairs' columns and weights).
 */
class QuadraticForm
{
public:
  explicit QuadraticForm(const dealii::SparseMatrix<double>& A);
  double operator()(const dealii::Vector<double>& x) const;
  /// Whether the pairs are stored by offset (see the class comment).
  bool banded() const { return band; }

private:
  void store_as_band();

  bool band = false;
  std::vector<double> diagonal;
  std::vector<unsigned int> row_start, column; ///< the pairs j > i by row i
  std::vector<double> weight;
  std::vector<unsigned int> offsets;          ///< the band: offsets j - i of the pairs
  std::vector<std::vector<double>> by_offset; ///< weight of (i, i + offsets[k]) at [k][i]
};

/**
 * The energy E(q, v, t) of SemiDiscreteSystem::energy, for evaluation again
 * and again on one system (the energy guard, RunGuard): v^T M v / 2 and
 * q^T K q / 2 as QuadraticForm objects (stored by offset on the FDM and FEM
 * grids). On the paper's FDM grid (N+1 = 500) an evaluation takes about
 * 0.8 us (3.3 us with the pairs row by row, a third of the two sparse-matrix
 * passes of SemiDiscreteSystem::energy). The same value up to round-off (the
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
