#pragma once

#include <pantocat/lac/interleaved_columns.h>
#include <pantocat/lac/sparse_direct_solver.h>
#include <pantocat/lac/sparse_row.h>

#include <deal.II/lac/vector.h>

#include <array>
#include <vector>

namespace pantocat
{
/**
 * InterleavedColumns that know the rows outside which they are zero (their
 * reach): the columns A^-1 G^T of a moving contact, which an implicit step
 * computes again every step (its row G moves), reads and resets. Solved by
 * SparseDirectSolver::solve_local(), they reach a few dozen rows on each
 * side of the contact (A^-1 decays exponentially away from it when the mass
 * term dominates, as in every implicit step here), so each of these
 * operations costs O(reach), not O(n).
 *
 * The operations that could write outside the reach are not offered; the
 * ones that do (add_row(), solve(), set()) extend it.
 */
class LocalColumns : private InterleavedColumns
{
public:
  using InterleavedColumns::dot;
  using InterleavedColumns::dots;
  using InterleavedColumns::size;
  using InterleavedColumns::width;

  /// n entries per column, all zero.
  void reinit(unsigned int n);
  /// Sets the entries of the reach to zero; the reach is empty then.
  void clear();
  /// column k += factor * row^T; the reach takes in the row's entries.
  void add_row(unsigned int k, const SparseRow& row, double factor);
  /// Entry i of column k = value; the reach takes in row i.
  void set(unsigned int i, unsigned int k, double value);
  /// Every column <- A^-1 column (SparseDirectSolver::solve_local()).
  void solve(const SparseDirectSolver& A);
  /// Row i of every column *= scaling[i] on the reach.
  void scale_rows(const dealii::Vector<double>& scaling);

  double operator()(unsigned int i, unsigned int k) const
  {
    return InterleavedColumns::operator()(i, k);
  }
  const double* data() const { return InterleavedColumns::data(); }
  /// The rows outside which every entry is zero, in increasing order.
  const RowRanges& reach() const { return rows; }
  /// out += sum_k coefficient[k] * column k, on the reach.
  void add_combination(const std::array<double, width>& coefficient,
                       dealii::Vector<double>& out) const;

private:
  /// The reach takes in the sorted rows @p sorted.
  void take_in(const std::vector<unsigned int>& sorted);

  RowRanges rows;
  std::vector<unsigned int> scratch;
  RowRanges added, merged; ///< take_in()'s workspace: no allocation once grown
};

/// The union of @p a and @p b (disjoint ranges in increasing order each).
RowRanges union_of(const RowRanges& a, const RowRanges& b);
/// @p out = the union of @p a and @p b (as union_of(), into @p out's memory).
void merge_ranges(const RowRanges& a, const RowRanges& b, RowRanges& out);
/// @p into = the union of @p into and @p b; @p scratch is workspace.
void add_ranges(RowRanges& into, const RowRanges& b, RowRanges& scratch);
} // namespace pantocat
