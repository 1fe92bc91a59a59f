#pragma once

#include <pantocat/lac/column_runs.h>
#include <pantocat/lac/sparse_row.h>

#include <deal.II/lac/vector.h>

#include <array>
#include <cstddef>
#include <vector>

namespace pantocat
{
/// The entries of @p column above 1e-16 of its largest one (a column A^-1 G^T
/// of a wire decays exponentially away from the constraint).
SparseRow truncated(const dealii::Vector<double>& column);

/**
 * The truncated columns X_l (l = 0 .. m-1, e.g. S^-1 G_l^T of the fixed
 * constraints) stored by unknown, so that both products an implicit step
 * needs cost about their non-zeros only:
 *  - g X for a sparse row g (a moving contact's rows against all the fixed
 *    columns: a few unknowns, each seen by the few columns that reach it);
 *  - X c for coefficients c (the forces of all fixed constraints at once).
 *
 * For g X, the rows of X are kept in slices of four reached unknowns, each
 * with the columns that reach any of them, in order (a dropper's column
 * decays away from it, so neighbouring unknowns are reached by nearly the
 * same columns). For X c, each column is kept as runs of consecutive
 * unknowns (a column of a FEM wire is one or two runs): X c sums column by
 * column into an accumulator, four unknowns at once along a run, then adds
 * the accumulator to y on the reached unknowns and clears it. Where the
 * runs are short (under four entries on average: an FDM's M^-1 G^T, a
 * dropper's two nodes), X c runs down the slices instead, four unknowns at
 * once, each unknown's sum in the same order. (Adding the
 * products of unknowns that one column alone reaches straight into y was
 * tried: 135-138 instead of 125 us per FEM + BDF-2 step at 200 droppers
 * 5 m apart.) Each unknown's sum takes its products in
 * the order of the columns, from +0: the value of the sum over its entries
 * alone, to the bit, however the columns overlap.
 */
class TruncatedColumns
{
public:
  /**
   * Stores @p columns (vectors of @p n_dofs entries) and, if given, their
   * @p partners X'_l (the same constraints' second columns, e.g. S^-1 (c G^T
   * + D M^-1 G^T) beside S^-1 G^T in GglFixedBlock) on the union of both
   * patterns, so that add_with_partners() reads each index once for both.
   */
  void initialize(const std::vector<SparseRow>& columns, unsigned int n_dofs,
                  const std::vector<SparseRow>& partners = {});

  /// Entries of the pattern (shared by the partners; without the slices' zeros).
  std::size_t n_entries() const { return pattern_entries; }
  /// Four-double multiply-adds of a pass over the slices with one sum per
  /// stored set: their columns times the sets (GglFixedBlock's cost model,
  /// fitted when X c ran over the slices).
  std::size_t n_slice_operations() const;

  /// out[l] = g . X_l for every column l (out is resized to m).
  void row_products(const SparseRow& g, std::vector<double>& out) const;
  /// out[l] = g . X'_l for every partner column l.
  void partner_row_products(const SparseRow& g, std::vector<double>& out) const;
  /// y += sum_l c[l] X_l, on the unknowns that some column reaches only.
  void add(const std::vector<double>& c, dealii::Vector<double>& y) const;
  /// y += sum_l c[l] X_l and z += sum_l d[l] X_l in one pass (each sum as add() makes
  /// it).
  void add(const std::vector<double>& c, dealii::Vector<double>& y,
           const std::vector<double>& d, dealii::Vector<double>& z) const;

  /**
   * y += sum_l c[l] X_l and then y += sum_l d[l] X'_l: on each unknown the
   * two sums and the two additions of add(c, y) on X and on X' (the same
   * value, to the bit).
   */
  void add_with_partners(const std::vector<double>& c, const std::vector<double>& d,
                         dealii::Vector<double>& y) const;

  /**
   * Sums left for the caller to add: first = sum_l c[l] X_l on the unknowns
   * first_rows (the rows some column reaches), second = sum_l d[l] X_l (sum())
   * or sum_l d[l] X'_l (sum_with_partners()) on second_rows; 0 elsewhere. The
   * caller adds them (y_i += first_i, then y_i += second_i for a partner sum:
   * what add() and add_with_partners() do) and sets them to 0 again.
   */
  struct Sums
  {
    double* first;
    double* second;
    const RowRanges* first_rows;
    const RowRanges* second_rows;
  };
  /// True if X c goes by the runs (their mean length is 4 or more); sum() and
  /// sum_with_partners() are offered then only.
  bool adds_by_runs() const { return by_runs; }
  /// The stretches of rows that the columns of each set reach, together.
  std::size_t n_row_ranges() const
  {
    return column_runs[0].reached().size() + column_runs[1].reached().size();
  }
  /// The sum of add(c, y), not added (second and second_rows null).
  Sums sum(const std::vector<double>& c) const;
  /// The sums of add(c, y, d, z), not added.
  Sums sum(const std::vector<double>& c, const std::vector<double>& d) const;
  /// The sums of add_with_partners(c, d, y), not added.
  Sums sum_with_partners(const std::vector<double>& c,
                         const std::vector<double>& d) const;

  /**
   * Four reached unknowns (-1: an unused lane) and the `length` columns that
   * reach any of them, ascending, at column[first ...]; the value of lane j,
   * the slice's k-th column, set s (0: X, 1: X') at value[offset + 4 (sets
   * k + s) + j], 0 where that column misses the unknown. Bit s of
   * reached_by[j]: set s reaches lane j.
   */
  struct Slice
  {
    std::size_t first = 0, offset = 0;
    unsigned int length = 0;
    std::array<int, 4> unknown{{-1, -1, -1, -1}};
    std::array<unsigned char, 4> reached_by{{0, 0, 0, 0}};
  };

private:
  /// The entries of one set (0: X, 1: X') on the shared pattern.
  void row_products(const SparseRow& g, unsigned int set, std::vector<double>& out) const;

  unsigned int m = 0;
  unsigned int sets = 1; ///< 2 with partners
  std::size_t pattern_entries = 0;
  std::vector<Slice> slices;
  std::vector<int> slot; ///< unknown i: 4 slice + lane, or -1 (no column reaches it)
  std::vector<unsigned int> column; ///< the slices' columns (Slice)
  std::vector<double> value;        ///< the slices' values (Slice)
  ColumnRuns column_runs[2];        ///< of X and of X'
  /// add() and add_with_partners() by the runs (else by the slices).
  bool by_runs = true;

  /// The sums of X c and X d (zero between calls).
  mutable std::vector<double> acc, acc_d;
  mutable RowRanges reach_w[2]; ///< the sums' rows when not every column counts
};
} // namespace pantocat
