#pragma once

#include <pantocat/lac/column_runs.h>
#include <pantocat/lac/interleaved_columns.h>
#include <pantocat/lac/sparse_direct_solver.h>
#include <pantocat/lac/sparse_row.h>
#include <pantocat/constrained_fast/mass_inverse.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace pantocat
{
/**
 * The Schur complement S = G_F A^-1 G_F^T + C of the constraints with
 * constant rows G_F (droppers, carrier supports: (31)) for a constant
 * symmetric positive definite A (M, or M + dt/2 D of (39), (41) for the
 * half-explicit method; the iteration matrix K + c_D D + c_M M of the
 * generalized-alpha method) and a constant diagonal C >= 0 (the compliance
 * of elastic droppers in an implicit step, 0 for rigid ones): the matrix of
 * the multiplier systems restricted to those constraints.
 *
 * S does not change during a run, so it is computed once, from one
 * application of A^-1 per constraint. It is stored sparse: an entry is kept
 * when |S_kl| > 1e-15 sqrt(S_kk S_ll) (A^-1 of a wire decays exponentially
 * along it, so the dropped entries are below round-off of the multipliers;
 * for a diagonal A, S is sparse exactly). Its unknowns are renumbered by
 * Cuthill-McKee, which makes S banded with a half bandwidth b of a few
 * (constraints along a section couple only to their neighbours).
 *
 * For each set of active constraints (select()) S restricted to them is
 * factorised by SparseDirectSolver (banded Cholesky): O(m b^2) when the active
 * set changes, O(m b) per solve. A diagonal S (the FDM's droppers and
 * supports with a diagonal A) is inverted entry by entry instead. A change of the active
 * set thus costs a refactorisation of this small banded matrix, never of A, and a step
 * costs O(m), not O(m^3) as a dense multiplier system would.
 *
 * The columns A^-1 G_k^T are kept too, truncated to their entries above
 * 1e-16 of the largest (a few dozen nodes each side of the constraint for a
 * FEM wire; the row's pattern for a diagonal A): the force G_F^T lambda then
 * enters the state in O(m) work, without a solve with A. When the columns
 * hold more entries than one solve with A reads (many constraints on a FEM
 * grid), they are dropped and add_columns() solves once with G_F^T lambda.
 */
class FixedConstraintSchur
{
public:
  /**
   * column <- A^-1 row^T, for a column that is zero on entry; the second
   * function sets the column to zero again (cheaply where A^-1 row^T is sparse).
   */
  struct ColumnSolver
  {
    std::function<void(const SparseRow&, dealii::Vector<double>&)> apply, reset;
    /// x <- A^-1 x, and the entries one such solve reads (its cost).
    std::function<void(dealii::Vector<double>&)> solve;
    /// Every column of X <- A^-1 column, side by side (one sweep when factorised).
    std::function<void(InterleavedColumns&)> solve_columns;
    double solve_cost = 0.;
    /// Keep the truncated columns whatever they cost (columns() is needed).
    bool keep_columns = false;
    /// Two right-hand sides are solved one after the other rather than side
    /// by side (the factor has twisted blocks: SparseDirectSolver).
    bool solve_one_at_a_time = false;
  };
  /// A^-1 given by a MassInverse, respectively a factorisation.
  static ColumnSolver column_solver(const MassInverse& A, bool keep_columns = false);
  static ColumnSolver column_solver(const SparseDirectSolver& A,
                                    bool keep_columns = false);

  /**
   * Computes S for the rows @p rows (of vectors of @p n_dofs unknowns) and the
   * inverse @p A; @p what names S in errors (a singular S: dependent
   * constraints). @p compliance, if not empty, is the diagonal C (one entry per row).
   */
  void initialize(const std::vector<const SparseRow*>& rows, const MassInverse& A,
                  unsigned int n_dofs, const std::string& what,
                  const std::vector<double>& compliance = {});
  /// The same for A given by its factorisation.
  void initialize(const std::vector<const SparseRow*>& rows, const SparseDirectSolver& A,
                  unsigned int n_dofs, const std::string& what,
                  const std::vector<double>& compliance = {});
  /// The same for any A (given by @p A's functions).
  void initialize(const std::vector<const SparseRow*>& rows, const ColumnSolver& A,
                  unsigned int n_dofs, const std::string& what,
                  const std::vector<double>& compliance);

  unsigned int size() const { return n; }
  /// Number of stored entries of S (for the benchmarks' reports).
  std::size_t n_nonzero_entries() const { return entries.n_nonzero_elements(); }

  /**
   * Restricts the solves to the constraints k with @p keep[k] (the others'
   * multipliers are 0); refactorises only if the selection changed.
   */
  void select(const std::vector<bool>& keep);

  /// y += sum_k factors[k] A^-1 G_k^T (the truncated columns, or one solve).
  void add_columns(const std::vector<double>& factors, dealii::Vector<double>& y) const;
  /// y += sum_k f[k] A^-1 G_k^T and z += sum_k g[k] A^-1 G_k^T in one pass over the
  /// columns.
  void add_columns(const std::vector<double>& f, dealii::Vector<double>& y,
                   const std::vector<double>& g, dealii::Vector<double>& z) const;
  /// The truncated columns A^-1 G_k^T, kept only with ColumnSolver::keep_columns
  /// (add_columns() reads their flat copy).
  const std::vector<SparseRow>& truncated_columns() const { return columns; }
  /// out = (G_F A^-1 G_F^T) in over all constraints (no selection, no compliance).
  void vmult(dealii::Vector<double>& out, const dealii::Vector<double>& in) const;
  /// Row k of vmult(): sum_l S_kl in[l], summed in vmult()'s order (the same bits).
  double row_product(const unsigned int k, const double* in) const
  {
    double s = 0.;
    for (unsigned int e = row_start[k]; e < row_start[k + 1]; ++e)
      s += row_value[e] * in[row_column[e]];
    return s;
  }
  /// Number of stored entries of the truncated columns.
  std::size_t n_column_entries() const;
  /// Calls @p f(l) for each constraint l with a stored entry S_kl (k too).
  template <typename F>
  void for_each_coupled(const unsigned int k, const F& f) const
  {
    for (unsigned int e = row_start[k]; e < row_start[k + 1]; ++e)
      f(row_column[e]);
  }

  /**
   * Marks in @p reached (one flag per constraint, set, never cleared) the
   * constraints among @p among whose multipliers in a solve with S restricted
   * to @p among take more than @p epsilon of those of @p sources (and the
   * sources): a best-first walk over S's stored entries that reaches l with the
   * largest product of scaled couplings |S_kl| / sqrt(S_kk S_ll) along a path
   * from a source (a source with 1), and goes on from l while that product
   * exceeds @p epsilon. For the S of constraints along wires (diagonally
   * dominant, each coupled to its neighbours) the product bounds l's share
   * of the sources' multipliers (the Neumann series of S scaled to a unit
   * diagonal). O(the constraints reached and their entries).
   */
  void reach_from(const std::vector<unsigned int>& sources,
                  const std::vector<bool>& among, double epsilon,
                  std::vector<bool>& reached) const;

  /// S restricted to a few constraints R, factorised dense (Cholesky).
  struct SubsetFactor
  {
    /// x <- S_RR^-1 x (x in R's order).
    void solve(double* x) const;
    unsigned int size() const { return rhs.size(); }

  private:
    friend class FixedConstraintSchur;
    dealii::FullMatrix<double> matrix, factor, factor_transposed; ///< S_RR, L, L^T
    mutable dealii::Vector<double> rhs, solution;
  };
  /**
   * Factorises S restricted to the few constraints @p subset (compliance
   * included), dense (Cholesky), into @p out: for a subset of a few dozen at
   * most, whose factor changes from step to step.
   */
  void factorize_subset(const std::vector<unsigned int>& subset, SubsetFactor& out) const;
  /// The same into this object's own factor, for solve_subset().
  void factorize_subset(const std::vector<unsigned int>& subset)
  {
    factorize_subset(subset, own_subset);
  }
  /// x <- S_RR^-1 x for the subset R of factorize_subset() (x in its order).
  void solve_subset(double* x) const { own_subset.solve(x); }

  /// x <- S_KK^-1 x on the kept constraints K, 0 on the others.
  void solve(dealii::Vector<double>& x) const;
  /// The same for several vectors, substituted side by side (four at a time).
  void solve(const std::vector<dealii::Vector<double>*>& xs) const;

private:
  unsigned int n = 0;
  std::string what;
  std::vector<SparseRow> columns; ///< A^-1 G_k^T, truncated (keep_columns only)
  ColumnRuns column_runs;         ///< the same columns by runs (or none)
  std::vector<SparseRow> rows;    ///< G_k, when the columns are dropped
  std::function<void(dealii::Vector<double>&)> solve_with_A;
  std::function<void(InterleavedColumns&)> solve_columns_with_A;
  bool solve_one_at_a_time = false;     ///< ColumnSolver::solve_one_at_a_time
  mutable dealii::Vector<double> work;  ///< G_F^T lambda, when the columns are dropped
  mutable InterleavedColumns work_pair; ///< G_F^T f and G_F^T g, side by side
  mutable std::vector<double> interleaved;
  std::vector<unsigned int> new_index; ///< Cuthill-McKee position of constraint k
  dealii::SparsityPattern pattern;     ///< in the new numbering
  dealii::SparseMatrix<double> entries, selected_matrix;
  std::vector<double> compliance; ///< C, in the original numbering
  std::vector<char> selected;     ///< select()'s keep, one byte each (the solves' loops)
  bool factorised = false;
  SparseDirectSolver factor;
  /// S is diagonal (no two constraints share an unknown of a diagonal A): the
  /// solves are scalings by inverse_diagonal (0 off the selection), no factor.
  bool diagonal_only = false;
  std::vector<double> diagonal, inverse_diagonal; ///< original numbering
  mutable dealii::Vector<double> permuted;
  /// S in the original numbering, compressed rows (vmult()).
  std::vector<unsigned int> row_start, row_column;
  std::vector<double> row_value;
  std::vector<double> row_coupling; ///< |S_kl| / sqrt(S_kk S_ll) of row_value's entries
  /// reach_from()'s workspace: the best product found per constraint (0: none),
  /// the constraints with one, and the walk's queue.
  mutable std::vector<double> reach_weight;
  mutable std::vector<unsigned int> reach_touched;
  mutable std::vector<std::pair<double, unsigned int>> reach_queue;
  SubsetFactor own_subset; ///< factorize_subset(subset)
  /// factorize_subset()'s workspace: the slots of R's constraints (-1 elsewhere).
  mutable std::vector<int> subset_slot;
};
} // namespace pantocat
