#pragma once

#include <cstddef>
#include <vector>

namespace pantocat
{
/**
 * The twisted ("burn at both ends") Cholesky factor of one long block of a
 * symmetric positive definite band matrix, for solves with one right-hand
 * side.
 *
 * A substitution with the plain factor A = U^T U is one recurrence down the
 * block and one up: each row waits for the row before (a multiply and a
 * subtract, about 8 cycles), so the solve of one right-hand side is
 * latency-bound, and its time is the block's length. The twisted factor
 * orders the block's rows as: the top [first, t) downwards, the bottom
 * [t + M, last) upwards, then the M middle rows [t, t + M), with t near the
 * middle and M = KD or KD + 1 so that top and bottom are equally long; with
 * that order P, P A P^T = R^T R. R has no more entries
 * than U (top and bottom are bands of half bandwidth KD, each coupled to the
 * middle only). R^T y = b runs from the top down and from the bottom up,
 * side by side, and ends in the middle; R x = y starts in the middle and
 * runs outwards, side by side: each recurrence is half as long.
 *
 * R is made by LAPACK: its top rows (and their coupling C_T to the middle)
 * are the plain factor's, its bottom rows (and C_B) the banded Cholesky
 * factor (dpbtrf) of the rows [t, last) in reverse order, its middle the
 * Cholesky factor (dpotrf) of the Schur complement A_MM - C_T^T C_T -
 * C_B^T C_B. The coefficients are stored in the order the chains read
 * them, the top's and the bottom's side by side in one record per step
 * (1 / R(i, i), then R's row over R(i, i)): a step of both chains is one
 * SSE2 operation per term. A record equal to the bit to one of the four
 * steps before is stored once, and the chains read each step's record
 * through a 4-byte offset: on a uniform wire the factor settles to records
 * that repeat (period 1 on a string, 4 on a twisted Hermite beam), so a
 * solve streams the offsets instead of 64 bytes of record per step
 * (doc/benchmarks.md, session 31).
 */
class TwistedBand
{
public:
  /// Half bandwidths a block may have.
  static constexpr int max_bandwidth = 4;

  /**
   * Twists the rows [first, last), half bandwidth @p bandwidth (1 to 4,
   * at least 4 bandwidth rows), of the matrix whose upper band is
   * @p matrix and whose plain Cholesky factor is @p factor (both in LAPACK's
   * upper band storage with half bandwidth @p kd >= @p bandwidth). Returns
   * false, leaving it without a factor, if the block is not eligible or LAPACK
   * reports a matrix that is not positive definite.
   */
  bool factorize(int first, int last, int bandwidth, int kd,
                 const std::vector<double>& matrix, const std::vector<double>& factor);

  /// The first of the middle rows.
  int twist() const { return t; }
  /// The records the chains read, each stored once (0 without a factor).
  std::size_t distinct_records() const
  {
    return (forward.size() + backward.size()) / (kd_block + 1);
  }
  /// The chains' steps: two per row of the top (or bottom), down and up.
  std::size_t substitution_steps() const
  {
    return forward_at.size() + backward_at.size();
  }

  /// x <- A^{-1} x on the block's rows of @p x (the whole vector's entries).
  void solve(double* x) const;
  /// solve() of two blocks side by side: four chains in flight.
  static void solve_pair(const TwistedBand& a, const TwistedBand& b, double* x);

  /// Two doubles in one SSE2 register (GCC's vector extension): the
  /// coefficients of the two chains a step takes, side by side.
  using Pair = double __attribute__((vector_size(16)));

private:
  int first = 0, t = 0, middle_size = 0, kd_block = 0, rows_per_lane = 0;
  /// The chains' records, a step's in one Pair each (top row, bottom row):
  /// 1 / R(i, i), then R(i, i -+ m) / R(i, i) for the rows m = KD, ..., 1
  /// before it in the chain's direction (zero beyond the block). R^T y = b:
  /// the top down and the bottom up; R x = y: the top up and the bottom down.
  std::vector<Pair> forward, backward;
  /// Where step s's record starts in forward (backward): a record equal to
  /// one of the four steps before, to the bit, is stored once (on a uniform
  /// grid nearly all are), so the chains stream offsets, not records.
  std::vector<unsigned int> forward_at, backward_at;
  /// The middle rows' records: 1 / R(j, j), the KD rows before it (top and
  /// middle) and the KD after it (bottom) for R^T y = b, and the KD after
  /// it (middle) for R x = y, each over R(j, j), zero where there is no row.
  std::vector<double> middle;

  /// R^T y = b and R x = y on the middle rows.
  template <int KD>
  void substitute_middle(double* x) const;
  /// The substitutions of one or two blocks (KB = 0: @p b is not used).
  template <int KA, int KB>
  static void substitute(const TwistedBand& a, const TwistedBand* b, double* x);
};
} // namespace pantocat
