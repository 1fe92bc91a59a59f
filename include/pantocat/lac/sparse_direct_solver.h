#pragma once

#include <pantocat/lac/twisted_band.h>

#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <memory>
#include <string>
#include <vector>

namespace pantocat
{
/// The sparse direct solver behind SparseDirectSolver (`Linear solver` in the prm).
enum class LinearSolverType
{
  banded,      ///< banded Cholesky (LAPACK dpbtrf) where the matrix allows, else UMFPACK
  umfpack,     ///< deal.II's SparseDirectUMFPACK
  trilinos_klu ///< Trilinos Amesos KLU through deal.II's TrilinosWrappers (needs MPI)
};

const char* to_string(LinearSolverType type);

/// The rows [first, last) of a vector.
struct RowRange
{
  int first = 0, last = 0;
};
/// Disjoint row ranges in increasing order.
using RowRanges = std::vector<RowRange>;
/**
 * A factorised sparse matrix: factorise once, solve many times. The implicit
 * integrators use it for their constant iteration matrices.
 *
 * The semi-discrete matrices are banded within each body (half bandwidth 1
 * to 3, no coupling between bodies), and symmetric positive definite. Such a
 * matrix is factorised by LAPACK's banded Cholesky (dpbtrf) and solved by a
 * forward and a backward substitution on the band (about four times faster
 * than UMFPACK at 1500 unknowns, doc/benchmarks.md; the substitution is
 * written out because the reference BLAS behind dpbtrs is slower still).
 * The factor inherits the block structure of the matrix: each block of
 * unknowns that no entry couples to another (carrier, contact wire,
 * pantograph) is substituted with its own half bandwidth. A long block is
 * also twisted (TwistedBand): the solves with one right-hand side substitute
 * it from both ends, which halves their latency-bound chains.
 * Any other matrix goes to deal.II's UMFPACK.
 */
class SparseDirectSolver
{
public:
  SparseDirectSolver();
  ~SparseDirectSolver();

  /// Half bandwidth above which `banded` goes to UMFPACK for the iteration matrices.
  static constexpr int default_max_bandwidth = 16;

  /**
   * Factorises @p matrix with @p type; throws SimulationError naming @p what if
   * it is singular. `banded` takes the banded Cholesky path if the half
   * bandwidth is at most @p max_bandwidth (a wider band pays off for the small
   * Schur complements of the constraints, FixedConstraintSchur).
   */
  void factorize(const dealii::SparseMatrix<double>& matrix, const std::string& what,
                 LinearSolverType type = LinearSolverType::banded,
                 int max_bandwidth = default_max_bandwidth);
  /// x <- A^{-1} x
  void solve(dealii::Vector<double>& x) const;
  /**
   * Solves for @p k right-hand sides at once (1 <= k <= 4), stored interleaved:
   * X[i k + r] is entry i of right-hand side r. The k substitutions run side
   * by side, so k solves cost little more than one (their recurrences are
   * latency-bound, not throughput-bound).
   */
  void solve_interleaved(double* X, unsigned int k) const;
  /**
   * solve_interleaved() for @p k right-hand sides that vanish outside the rows
   * @p reach, and whose solutions are negligible far from them: the
   * columns A^-1 G^T of a contact's row, which decay exponentially away from
   * it (the mass term of an implicit step's matrix dominates).
   *
   * In each uncoupled block of the band that @p reach meets, the forward
   * substitution starts at the block's first row of @p reach (the rows before
   * it are zero) and stops, past its last one, at the end of a run of
   * `local_run` rows on which every column is below `local_tolerance` times
   * its largest entry so far; the backward substitution starts there (the
   * rows after it taken as zero) and stops likewise before the first row.
   * Each computed row takes the operations of solve_interleaved() in its
   * order; what is dropped is below 1e-20 of the column's largest entry and,
   * in the rows kept, changes them by about 1e-20 times the decay over the
   * run (see doc/dynamics.md). @p reach is replaced by the rows computed;
   * entries of @p X outside them must be zero on entry and stay zero.
   * Without the banded path: solve_interleaved() and @p reach = all rows.
   */
  void solve_local(double* X, unsigned int k, RowRanges& reach) const;
  /// Rows per convergence check of solve_local().
  static constexpr int local_run = 16;
  /// Relative size below which solve_local() stops substituting.
  static constexpr double local_tolerance = 1e-20;

  /// True if the banded Cholesky path is used.
  bool is_banded() const { return banded; }
  /// True if some block has a twisted factor: a solve with one right-hand
  /// side then takes about half the time of one with two side by side.
  bool has_twisted_blocks() const { return !twisted.empty(); }
  /// Entries of the factor read by one solve (n (2 kd + 1) when banded; an
  /// estimate of 16 per unknown otherwise): the cost model of FixedConstraintSchur.
  double solve_cost() const { return banded ? n * (2. * kd + 1.) : 16. * n; }

  /// A range of unknowns [first, last) not coupled to the others, with its half
  /// bandwidth.
  struct Block
  {
    int first = 0, last = 0, bandwidth = 0;
    /// 0, or the first middle row of the block's twisted factor
    /// (TwistedBand; long blocks of half bandwidth 1 to 4), which the solves
    /// with one right-hand side use.
    int twist = 0;
  };
  /// The banded factor as the substitutions read it (see lower_scaled, upper_scaled).
  struct ScaledBand
  {
    const double* lower; ///< U(j - m, j) / U(j, j), at the places of U in the band
    const double* upper; ///< U(i, i + m) / U(i, i), likewise
    const double* recip; ///< 1 / U(i, i)
    int kd;              ///< the factor's half bandwidth (its storage)
  };

  /// The uncoupled blocks of the banded factor (empty on the UMFPACK path).
  const std::vector<Block>& blocks() const { return independent_blocks; }
  /// The twisted factors' distinct records over their substitution steps
  /// (TwistedBand::distinct_records()); 0 without twisted blocks.
  double twisted_record_fraction() const;

private:
  bool try_banded_cholesky(const dealii::SparseMatrix<double>& matrix, int max_bandwidth);
  void find_blocks(const dealii::SparseMatrix<double>& matrix);
  /// One right-hand side with UMFPACK or KLU.
  void solve_general(dealii::Vector<double>& x) const;

  struct Klu; ///< Trilinos matrix and Amesos KLU solver
  std::unique_ptr<Klu> klu;
  bool banded = false;
  int n = 0, kd = 0;
  std::vector<double> reciprocal; ///< 1 / U(i, i) of the Cholesky factor U
  /// U(i, j) / U(j, j) and U(i, j) / U(i, i) in LAPACK's upper band storage
  /// (U(i, j), i <= j <= i + kd, at (kd + i - j) + j (kd + 1)):
  /// the substitutions' coefficients (one multiply-subtract per row on the
  /// recurrence's path instead of the row's whole sum and a scaling).
  std::vector<double> lower_scaled, upper_scaled;
  /// The scaled factor as the substitutions read it.
  ScaledBand scaled_band() const;
  std::vector<Block> independent_blocks;
  /// The twisted factor of each block with Block::twist (else empty).
  std::vector<TwistedBand> twisted;
  dealii::SparseDirectUMFPACK umfpack;
};
} // namespace pantocat
