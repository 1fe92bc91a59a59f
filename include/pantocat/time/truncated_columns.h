#pragma once

#include <pantocat/system/sparse_row.h>

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
 * The rows of X are kept in slices of four reached unknowns (the lanes of a
 * four-double vector), each with the columns that reach any of them, in
 * order (a dropper's column decays away from it, so neighbouring unknowns
 * are reached by nearly the same columns). X c then runs down a slice's
 * columns, four unknowns at once, and each unknown's sum takes its products
 * in the order of the columns, a zero where a column misses it: the value
 * of the sum over its entries alone, to the bit.
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
  /// stored set: their columns times the sets.
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
   * y += sum_l c[l] X_l and then y += sum_l d[l] X'_l, in one pass: on each
   * unknown the two sums and the two additions of add(c, y) on X and on X'
   * (the same value, to the bit).
   */
  void add_with_partners(const std::vector<double>& c, const std::vector<double>& d,
                         dealii::Vector<double>& y) const;

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
};
} // namespace pantocat
