#pragma once

#include <pantocat/lac/sparse_row.h>

#include <deal.II/lac/vector.h>

#include <array>
#include <vector>

namespace pantocat
{
/**
 * Up to four vectors of length n stored interleaved (entry i of column k at
 * i * 4 + k), the layout in which SparseDirectSolver::solve_interleaved()
 * substitutes four right-hand sides side by side. The implicit integrators
 * build their right-hand sides in it (sparse constraint rows), solve, read
 * the functionals of the solutions (dot products with sparse rows) and
 * combine the columns into the step's vectors, without copying them out.
 */
class InterleavedColumns
{
public:
  static constexpr unsigned int width = 4;

  /// n entries per column, all zero.
  void reinit(unsigned int n);
  /// Sets every entry to zero (keeps the size).
  void clear();

  unsigned int size() const { return n; }
  double* data() { return values.data(); }
  const double* data() const { return values.data(); }

  double& operator()(unsigned int i, unsigned int k) { return values[i * width + k]; }
  double operator()(unsigned int i, unsigned int k) const
  {
    return values[i * width + k];
  }

  /// column k += factor * row^T
  void add_row(unsigned int k, const SparseRow& row, double factor);
  /// row . column k
  double dot(const SparseRow& row, unsigned int k) const;
  /// row . column k for every k in one pass (each as dot(row, k) sums it).
  std::array<double, width> dots(const SparseRow& row) const;

  /// out += sum_k coefficient[k] * column k (one pass).
  void add_combination(const std::array<double, width>& coefficient,
                       dealii::Vector<double>& out) const;

private:
  unsigned int n = 0;
  std::vector<double> values;
};
} // namespace pantocat
