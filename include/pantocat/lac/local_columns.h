#pragma once

#include <pantocat/lac/interleaved_columns.h>
#include <pantocat/lac/sparse_direct_solver.h>
#include <pantocat/system/sparse_row.h>

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
  /// True if the reach meets the rows @p span (a row's products with the
  /// columns are +0 otherwise: dot() and dots() can be skipped).
  bool reaches(const RowRange& span) const
  {
    for (const RowRange& r : rows)
      if (r.first < span.last && r.last > span.first)
        return true;
    return false;
  }
  /// True if the reach meets one of the rows @p spans.
  bool reaches(const RowRanges& spans) const
  {
    for (const RowRange& span : spans)
      if (reaches(span))
        return true;
    return false;
  }

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

/**
 * Many rows, each given by its runs of consecutive unknowns (spans_of(): the
 * fixed constraints' rows), indexed for one question: which of them does a
 * moving constraint's columns' reach meet (LocalColumns::reaches() of each,
 * answered for all at once)? The runs are sorted by their first row, so a
 * range of the reach finds the runs that meet it by a binary search and
 * reads only those: O(log of the runs + the rows met) instead of a test per
 * row.
 */
class RowSpanIndex
{
public:
  /// Indexes the rows k = 0, 1, ... with the runs @p spans[k].
  void initialize(const std::vector<RowRanges>& spans);
  /// The rows k one of whose runs meets one of @p ranges (disjoint, in
  /// increasing order), into @p out, in increasing k, each once: the rows for
  /// which LocalColumns::reaches(spans[k]) is true when @p ranges is the reach.
  void rows_meeting(const RowRanges& ranges, std::vector<unsigned int>& out) const;

private:
  struct Run
  {
    int first, last;
    unsigned int row;
  };
  std::vector<Run> runs;         ///< sorted by first
  int longest = 0;               ///< the longest run's length
  mutable std::vector<char> met; ///< rows_meeting()'s flags (all 0 between calls)
};

/// @p out = the rows @p sorted (ascending, repeats allowed) as runs of
/// consecutive rows.
void runs_of(const std::vector<unsigned int>& sorted, RowRanges& out);
/// The rows of @p row's indices as runs of consecutive rows, in increasing
/// order (a dropper's row: a few rows of the carrier, a few of the contact
/// wire, far apart in the numbering).
RowRanges spans_of(const SparseRow& row);

/// The union of @p a and @p b (disjoint ranges in increasing order each).
RowRanges union_of(const RowRanges& a, const RowRanges& b);
/// @p out = the union of @p a and @p b (as union_of(), into @p out's memory).
void merge_ranges(const RowRanges& a, const RowRanges& b, RowRanges& out);
/// @p into = the union of @p into and @p b; @p scratch is workspace.
void add_ranges(RowRanges& into, const RowRanges& b, RowRanges& scratch);
} // namespace pantocat
