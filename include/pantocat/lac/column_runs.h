#pragma once

#include <pantocat/lac/sparse_direct_solver.h>
#include <pantocat/lac/sparse_row.h>

#include <cstddef>
#include <vector>

namespace pantocat
{
/**
 * Sparse columns X_l (truncated columns A^-1 G_l^T of fixed constraints:
 * FixedConstraintSchur, TruncatedColumns) kept as runs of consecutive
 * unknowns. A FEM wire's column is one or two runs, so X c streams along
 * them four unknowns at once, where a loop over the entries' indices would
 * gather and scatter one at a time.
 */
class ColumnRuns
{
public:
  /// A run of consecutive unknowns [first, first + length), its values at
  /// [offset, offset + length) of the stored values.
  struct Run
  {
    unsigned int first, length;
    std::size_t offset;
  };

  /// Stores @p columns (entries in increasing index order, vectors of
  /// @p n_dofs entries).
  void initialize(const std::vector<SparseRow>& columns, unsigned int n_dofs);
  /// No columns.
  void clear();

  std::size_t n_entries() const { return value.size(); }
  std::size_t n_runs() const { return runs.size(); }
  /// The rows that some column reaches, in increasing order.
  const RowRanges& reached() const { return ranges; }

  /**
   * y += c[l] X_l (and, with @p d, z += d[l] X_l) over the columns l, column
   * after column, each entry y_i += c[l] x_il (compiled for AVX2 beside the
   * baseline, without fused multiply-add: the same bits either way). A column
   * with c[l] = 0 (and d[l] = 0) is skipped.
   */
  void add(const double* c, const double* d, double* y, double* z) const;

  /**
   * The rows that the columns l with c[l] != 0 (or d[l] != 0) reach, into
   * @p out: reached() itself (@p out untouched, its address returned) when
   * every column counts, else their runs merged into @p out. What add()
   * writes lies in them.
   */
  const RowRanges* reach_of(const double* c, const double* d, RowRanges& out) const;

private:
  std::vector<Run> runs;
  std::vector<unsigned int> run_start{
      0}; ///< column l: runs[run_start[l] .. run_start[l + 1])
  std::vector<double> value;
  RowRanges ranges;
  mutable std::vector<RowRange> gathered; ///< reach_of()'s workspace
};
} // namespace pantocat
