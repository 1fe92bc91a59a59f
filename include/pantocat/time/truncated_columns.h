#pragma once

#include <pantocat/system/sparse_row.h>

#include <deal.II/lac/vector.h>

#include <cstddef>
#include <vector>

namespace pantocat
{
/// The entries of @p column above 1e-16 of its largest one (a column A^-1 G^T
/// of a wire decays exponentially away from the constraint).
SparseRow truncated(const dealii::Vector<double>& column);

/**
 * The truncated columns X_l (l = 0 .. m-1, e.g. S^-1 G_l^T of the fixed
 * constraints) stored by unknown (compressed rows of the n x m matrix X), so
 * that both products an implicit step needs cost their non-zeros only:
 *  - g X for a sparse row g (a moving contact's rows against all the fixed
 *    columns: a few unknowns, each seen by the few columns that reach it);
 *  - X c for coefficients c (the forces of all fixed constraints at once).
 */
class TruncatedColumns
{
public:
  /// Stores @p columns (vectors of @p n_dofs entries).
  void initialize(const std::vector<SparseRow>& columns, unsigned int n_dofs);

  std::size_t n_entries() const { return value.size(); }

  /// out[l] = g . X_l for every column l (out is resized to m).
  void row_products(const SparseRow& g, std::vector<double>& out) const;
  /// y += sum_l c[l] X_l, on the unknowns that some column reaches only.
  void add(const std::vector<double>& c, dealii::Vector<double>& y) const;
  /// y += sum_l c[l] X_l and z += sum_l d[l] X_l in one pass (each sum as add() makes
  /// it).
  void add(const std::vector<double>& c, dealii::Vector<double>& y,
           const std::vector<double>& d, dealii::Vector<double>& z) const;

private:
  unsigned int m = 0;
  std::vector<std::size_t> start; ///< entries of unknown i: [start[i], start[i+1])
  /// The unknowns with entries, in order: a lumped mass's columns reach two
  /// unknowns per dropper of thousands, and add() skips the others.
  std::vector<unsigned int> reached;
  std::vector<unsigned int> column;
  std::vector<double> value;
};
} // namespace pantocat
