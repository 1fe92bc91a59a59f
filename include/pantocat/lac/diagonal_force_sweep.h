#pragma once

#include <deal.II/lac/sparse_matrix.h>

#include <array>
#include <vector>

namespace pantocat
{
/**
 * K and D/2 of a semi-discrete system stored by diagonals (offsets -b..b,
 * zero-padded), as DiagonalForceSweep reads them: the operators are banded
 * within each body, and a diagonal sweep vectorises. The offsets on which an
 * operator vanishes are left out of its list.
 */
struct ForceDiagonals
{
  int bandwidth = 0;
  std::vector<int> stiffness_offsets, damping_offsets;
  std::vector<std::vector<double>> stiffness, half_damping; ///< [offset + b][row]

  ForceDiagonals() = default;
  /// From @p K and @p D, which share one sparsity pattern.
  ForceDiagonals(const dealii::SparseMatrix<double>& K,
                 const dealii::SparseMatrix<double>& D);
};

/**
 * The right-hand side of the half-explicit step (39) before its solve,
 * out = f - K q - D (v_{n-1} + v_n)/2, with K and D/2 stored by diagonals
 * (`[offset + b][row]`, offsets -b..b; the entries outside the matrix are 0).
 *
 * A uniform wire repeats its rows: the equal elements of a Hermite beam give
 * rows whose coefficients repeat with period 2 (displacement and rotation
 * rows alternate), those of a string with period 1. On runs of such rows the
 * sweep reads the two rows' coefficients kept aside instead of streaming the
 * 2 (2b + 1) diagonals from memory: with S55's 14 diagonals the streams,
 * not the arithmetic, set the pace once the grid outgrows the caches. It
 * sums eight rows at once (two four-double vectors), each row's terms in a
 * register until the row is done, with v_{n-1} + v_n formed once per row. Rows of a run
 * with coefficients of their own (point masses, supports) are its exceptions: swept with
 * the run's, then again from their own coefficients, four exceptions at once (one per
 * vector lane). The other rows (the ends, the pantograph) read the diagonals. Every row's
 * terms come in the order of the offsets, from the same coefficient values, so the result
 * is the same to the bit whichever way a row is swept.
 */
class DiagonalForceSweep
{
public:
  DiagonalForceSweep() = default;
  /// Not copied: it points to the diagonals of its owner.
  DiagonalForceSweep(const DiagonalForceSweep&) = delete;
  DiagonalForceSweep& operator=(const DiagonalForceSweep&) = delete;

  /// The stored diagonals (kept by reference: the integrator owns them).
  void initialize(int n, int bandwidth, const std::vector<int>& stiffness_offsets,
                  const std::vector<std::vector<double>>& stiffness,
                  const std::vector<int>& damping_offsets,
                  const std::vector<std::vector<double>>& half_damping);

  /// out <- f - K q - D (vp + v)/2.
  void apply(const double* f, const double* q, const double* vp, const double* v,
             double* out);

  /// Rows swept from coefficients kept aside, exceptions not counted (for the tests).
  int rows_in_runs() const;

  /// Runs shorter than this are swept by diagonals.
  static constexpr int minimum_run = 32;

private:
  /// Rows [first, last) whose coefficients are those of row first (even
  /// distance) or first + 1 (odd distance), per listed offset, but for the
  /// exceptions [first_exception, last_exception), swept again afterwards.
  struct Run
  {
    int first, last;
    std::size_t first_exception, last_exception;
    std::array<std::array<double, 2>, 7> k, d; ///< [offset index][parity]
  };
  void find_runs();
  bool same_coefficients(int i, int j) const;
  /// The exceptions' rows and coefficients in groups of four (sweep_exception_groups()).
  void group_exceptions();

  int n = 0, b = 0;
  const std::vector<int>* k_offsets = nullptr;
  const std::vector<std::vector<double>>* k = nullptr;
  const std::vector<int>* d_offsets = nullptr;
  const std::vector<std::vector<double>>* d = nullptr;
  std::vector<Run> runs;
  std::vector<int> exceptions; ///< rows of the runs with their own coefficients
  /// Their stiffness, then damping coefficients by offset, row after row.
  std::vector<double> exception_coefficients;
  /// The same, four exceptions per group: rows [group][lane], coefficients
  /// [group][term][lane].
  std::vector<int> grouped_rows;
  std::vector<double> grouped_coefficients;
  std::vector<double> velocity_sum; ///< v_{n-1} + v_n of a block of rows
};
} // namespace pantocat
