#pragma once

#include <pantocat/lac/interleaved_columns.h>
#include <pantocat/lac/local_columns.h>
#include <pantocat/lac/sparse_direct_solver.h>
#include <pantocat/lac/sparse_row.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

namespace pantocat
{
/**
 * The inverse of a constant symmetric positive definite matrix such as M or
 * M + dt/2 D of (39)-(41). Three forms, chosen from the matrix:
 *  - diagonal: a scaling (FDM wires);
 *  - diagonal except a few coupled rows (FDM wires with a lumped pantograph
 *    whose dampers couple its bodies): a scaling plus a small dense inverse
 *    of the coupled block;
 *  - otherwise a sparse direct factorisation (FEM).
 *
 * apply_to_row() computes A^{-1} r^T for a sparse row r. In the first two
 * forms the result lives on the pattern of r plus the coupled rows, and only
 * those entries are touched, so the column can be used and reset in O(nnz(r)).
 */
class MassInverse
{
public:
  void initialize(const dealii::SparseMatrix<double>& matrix, bool is_diagonal,
                  const std::string& what,
                  LinearSolverType solver = LinearSolverType::banded);

  /// x <- A^{-1} x
  void apply(dealii::Vector<double>& x) const;
  /// Every column of @p X <- A^{-1} column (one batched substitution when factorised).
  void apply(InterleavedColumns& X) const;
  /// The same for columns with a reach (SparseDirectSolver::solve_local() when
  /// factorised).
  void apply(LocalColumns& X) const;
  /**
   * In the diagonal forms: the scaling 1/A_ii, with 1 on the coupled rows, so
   * that A^{-1} x = apply_coupled_rows(row_scaling() .* x); null otherwise.
   */
  const dealii::Vector<double>* row_scaling() const
  {
    return diagonal ? &scaling : nullptr;
  }
  /// x[C] <- block^{-1} x[C] on the coupled rows C (diagonal forms only).
  void apply_coupled_rows(dealii::Vector<double>& x) const;
  /// The rows of the small coupled block of the diagonal forms (else empty).
  const std::vector<unsigned int>& coupled() const { return coupled_rows; }
  /// The sparse factorisation, or null when A is (block-)diagonal.
  const SparseDirectSolver* factorised() const
  {
    return diagonal ? nullptr : &factorization;
  }

  /// column <- A^{-1} row^T (column must be zero outside row's pattern when diagonal).
  void apply_to_row(const SparseRow& row, dealii::Vector<double>& column) const;

  /// Sets column to zero again after apply_to_row (O(nnz) when diagonal).
  void reset_column(const SparseRow& row, dealii::Vector<double>& column) const;

  /// y += factor * column, with column = A^{-1} row^T (O(nnz) when diagonal).
  void add_column(const SparseRow& row, const dealii::Vector<double>& column,
                  double factor, dealii::Vector<double>& y) const;

  /// One term factor * row^T of add_rows().
  struct RowTerm
  {
    const SparseRow* row;
    double factor;
  };
  /**
   * y += A^{-1} (sum of factor * row^T over @p terms): one application of
   * A^{-1} for all rows (O(sum nnz) in the diagonal forms, one solve when
   * factorised), instead of one column per row.
   */
  void add_rows(const std::vector<RowTerm>& terms, dealii::Vector<double>& y) const;

private:
  /// column[C] = block^{-1} row[C] for the coupled rows C.
  void apply_block_to_row(const SparseRow& row, dealii::Vector<double>& column) const;

  bool diagonal = false;
  dealii::Vector<double> inverse_diagonal; ///< 0 on the coupled rows
  dealii::Vector<double> scaling;          ///< 1 / A_ii, 1 on the coupled rows
  std::vector<unsigned int> coupled_rows;
  dealii::FullMatrix<double> coupled_inverse;
  mutable dealii::Vector<double> block_in, block_out;
  mutable dealii::Vector<double> work; ///< add_rows() when factorised
  SparseDirectSolver factorization;
};
} // namespace pantocat
