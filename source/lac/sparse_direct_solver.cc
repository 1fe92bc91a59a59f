#include <pantocat/base/input_error.h>
#include <pantocat/lac/sparse_direct_solver.h>

#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

extern "C"
{
  // LAPACK: Cholesky factorisation of a symmetric positive definite band matrix.
  void dpbtrf_(const char* uplo, const int* n, const int* kd, double* ab, const int* ldab,
               int* info);
}

namespace pantocat
{
namespace
{
/// Blocks at least this long are kept apart and twisted (TwistedBand): with
/// one right-hand side, substituted from both ends, two blocks at a time.
constexpr int long_block = 256;

/**
 * Row @p j of the forward substitution U^T y = b in the block that starts at
 * row @p first, with half bandwidth @p width, for K interleaved right-hand
 * sides: y_j = b_j / U(j, j) - sum_m (U(j - m, j) / U(j, j)) y_{j-m}, the
 * quotients read from @p l at the places of U(j - m, j) in the band
 * (SparseDirectSolver's lower_scaled). The term of the row just before comes
 * last: the recurrence waits one multiply-subtract per row, not the whole sum
 * and a division.
 */
template <int K>
inline void forward_row(const double* __restrict l, const int kd,
                        const double* __restrict recip, double* __restrict X, const int j,
                        const int first, const int width)
{
  double s[K];
  for (int r = 0; r < K; ++r)
    s[r] = X[j * K + r] * recip[j];
  const double* column = l + static_cast<std::size_t>(j) * (kd + 1) + kd;
  for (int m = width; m >= 1; --m)
    if (j - m >= first)
      for (int r = 0; r < K; ++r)
        s[r] -= column[-m] * X[(j - m) * K + r];
  for (int r = 0; r < K; ++r)
    X[j * K + r] = s[r];
}

/**
 * Row @p i of the backward substitution U x = y in the block that ends before
 * @p last: x_i = y_i / U(i, i) - sum_m (U(i, i + m) / U(i, i)) x_{i+m}, the
 * quotients read from @p u at the places of U(i, i + m) (upper_scaled).
 */
template <int K>
inline void backward_row(const double* __restrict u, const int kd,
                         const double* __restrict recip, double* __restrict X,
                         const int i, const int last, const int width)
{
  double s[K];
  for (int r = 0; r < K; ++r)
    s[r] = X[i * K + r] * recip[i];
  for (int m = width; m >= 1; --m)
    if (i + m < last)
      for (int r = 0; r < K; ++r)
        s[r] -=
            u[(kd - m) + static_cast<std::size_t>(i + m) * (kd + 1)] * X[(i + m) * K + r];
  for (int r = 0; r < K; ++r)
    X[i * K + r] = s[r];
}

/**
 * The band's terms of one row, for a wide band: sum_{m = 2}^{reach}
 * c(m) x_{row -+ m} in P partial sums per right-hand side, so that the
 * multiply-adds of a row do not wait for each other (one chain of @p reach
 * dependent operations per row would make a solve with one right-hand side
 * and a band a few dozen wide latency-bound). @p c(m) is the coefficient,
 * @p x(m) the row of X it multiplies.
 */
template <int K, int P, typename Coefficient, typename Row>
inline void band_terms(const int reach, const Coefficient& c, const Row& x, double* sum)
{
  double p[P][K] = {};
  int m = reach;
  for (; m >= P + 1; m -= P)
    for (int t = 0; t < P; ++t)
    {
      const double a = c(m - t);
      const double* y = x(m - t);
      for (int r = 0; r < K; ++r)
        p[t][r] += a * y[r];
    }
  for (; m >= 2; --m)
  {
    const double a = c(m);
    const double* y = x(m);
    for (int r = 0; r < K; ++r)
      p[0][r] += a * y[r];
  }
  for (int r = 0; r < K; ++r)
  {
    sum[r] = p[0][r];
    for (int t = 1; t < P; ++t)
      sum[r] += p[t][r];
  }
}

/**
 * forward_row() for a wide band (half bandwidth above 4: the Schur
 * complement of many close constraints with a consistent mass matrix) and
 * one or two right-hand sides: the terms m >= 2 by band_terms() in 4 / K
 * partial sums, then the row just before, last. (Three or four interleaved
 * right-hand sides are independent chains enough: forward_row().)
 */
template <int K>
inline void forward_row_wide(const double* __restrict l, const int kd,
                             const double* __restrict recip, double* __restrict X,
                             const int j, const int first, const int width)
{
  const int reach = std::min(width, j - first);
  const double* column = l + static_cast<std::size_t>(j) * (kd + 1) + kd;
  double sum[K];
  band_terms<K, 4 / K>(
      reach, [&](const int m) { return column[-m]; },
      [&](const int m) { return X + (j - m) * K; }, sum);
  for (int r = 0; r < K; ++r)
  {
    double s = X[j * K + r] * recip[j] - sum[r];
    if (reach >= 1)
      s -= column[-1] * X[(j - 1) * K + r];
    X[j * K + r] = s;
  }
}

/// backward_row() for a wide band, as forward_row_wide().
template <int K>
inline void backward_row_wide(const double* __restrict u, const int kd,
                              const double* __restrict recip, double* __restrict X,
                              const int i, const int last, const int width)
{
  const int reach = std::min(width, last - 1 - i);
  const auto coefficient = [&](const int m)
  { return u[(kd - m) + static_cast<std::size_t>(i + m) * (kd + 1)]; };
  double sum[K];
  band_terms<K, 4 / K>(
      reach, coefficient, [&](const int m) { return X + (i + m) * K; }, sum);
  for (int r = 0; r < K; ++r)
  {
    double s = X[i * K + r] * recip[i] - sum[r];
    if (reach >= 1)
      s -= coefficient(1) * X[(i + 1) * K + r];
    X[i * K + r] = s;
  }
}

using ScaledBand = SparseDirectSolver::ScaledBand;

/**
 * The KD rows a substitution solved last, for K interleaved right-hand
 * sides, kept in registers (w[m - 1]: the row m before the next one): the
 * next row reads them there, not from X, where each row would wait for the
 * store of the row before to reach its load (the recurrence is
 * latency-bound).
 */
template <int KD, int K>
struct Window
{
  double w[KD][K];

  /// Row @p x: x = x / U(row, row) - sum_{m = KD..1} c(m) w[m - 1] (the
  /// operations of forward_row() and backward_row(), in their order), then
  /// the window moves on by one row. Always inlined: the window stays in
  /// registers only inside the caller's loop (GCC left the FDM's chains, KD
  /// = 2, as calls).
  template <typename Coefficient>
  [[gnu::always_inline]] void step(double* x, const double recip, const Coefficient& c)
  {
    double s[K];
    for (int r = 0; r < K; ++r)
      s[r] = x[r] * recip;
    for (int m = KD; m >= 1; --m)
    {
      const double a = c(m);
      for (int r = 0; r < K; ++r)
        s[r] -= a * w[m - 1][r];
    }
    for (int r = 0; r < K; ++r)
      x[r] = s[r];
    for (int m = KD - 1; m >= 1; --m)
      for (int r = 0; r < K; ++r)
        w[m][r] = w[m - 1][r];
    for (int r = 0; r < K; ++r)
      w[0][r] = s[r];
  }
};

/**
 * The forward substitution of one block with a compile-time half bandwidth
 * KD > 0, row by row, with a Window of the rows solved last.
 */
template <int KD, int K>
struct ForwardChain
{
  const ScaledBand& f;
  double* __restrict X;
  int first, last;
  Window<KD, K> window;

  /// The rows [first, first + KD) as forward_row() does them, then the window.
  void start()
  {
    for (int j = first; j < std::min(last, first + KD); ++j)
      forward_row<K>(f.lower, f.kd, f.recip, X, j, first, KD);
    if (last - first > KD)
      for (int m = 1; m <= KD; ++m)
        for (int r = 0; r < K; ++r)
          window.w[m - 1][r] = X[(first + KD - m) * K + r];
  }

  /// Row j >= first + KD.
  [[gnu::always_inline]] void step(const int j)
  {
    const double* column = f.lower + static_cast<std::size_t>(j) * (f.kd + 1) + f.kd;
    window.step(X + j * K, f.recip[j], [column](const int m) { return column[-m]; });
  }
};

/// The backward substitution of one block, as ForwardChain (backward_row()'s operations).
template <int KD, int K>
struct BackwardChain
{
  const ScaledBand& f;
  double* __restrict X;
  int first, last;
  Window<KD, K> window;

  /// The rows [last - KD, last) as backward_row() does them, then the window.
  void start()
  {
    for (int i = last - 1; i >= std::max(first, last - KD); --i)
      backward_row<K>(f.upper, f.kd, f.recip, X, i, last, KD);
    if (last - first > KD)
      for (int m = 1; m <= KD; ++m)
        for (int r = 0; r < K; ++r)
          window.w[m - 1][r] = X[(last - 1 - KD + m) * K + r];
  }

  /// Row i < last - KD.
  [[gnu::always_inline]] void step(const int i)
  {
    const double* upper = f.upper;
    const int kd = f.kd;
    window.step(X + i * K, f.recip[i],
                [upper, kd, i](const int m)
                { return upper[(kd - m) + static_cast<std::size_t>(i + m) * (kd + 1)]; });
  }
};

/**
 * Forward (U^T y = b) and backward (U x = y) substitution on the rows
 * [first, last) of one uncoupled block with half bandwidth KD (a compile-time
 * constant, so that the loops unroll; KD < 0: the block's bandwidth @p bw at
 * run time), for K interleaved right-hand sides.
 */
template <int KD, int K>
void substitute(const ScaledBand& f, double* __restrict X, const int first,
                const int last, const int bw = 0)
{
  if constexpr (KD > 0)
  {
    ForwardChain<KD, K> forward{f, X, first, last, {}};
    forward.start();
    for (int j = first + KD; j < last; ++j)
      forward.step(j);
    BackwardChain<KD, K> backward{f, X, first, last, {}};
    backward.start();
    for (int i = last - 1 - KD; i >= first; --i)
      backward.step(i);
    return;
  }
  // Partial sums pay for one right-hand side; for two only in bands at least
  // 12 wide (measured on a 200-row band: two right-hand sides 4.5 instead of
  // 5.8 us at 18 wide, 3.0 instead of 2.7 us at 8 wide).
  if constexpr (KD < 0 && K <= 2)
    if (K == 1 || bw >= 12)
    {
      for (int j = first; j < last; ++j)
        forward_row_wide<K>(f.lower, f.kd, f.recip, X, j, first, bw);
      for (int i = last - 1; i >= first; --i)
        backward_row_wide<K>(f.upper, f.kd, f.recip, X, i, last, bw);
      return;
    }
  const int width = KD < 0 ? bw : KD;
  for (int j = first; j < last; ++j)
    forward_row<K>(f.lower, f.kd, f.recip, X, j, first, width);
  for (int i = last - 1; i >= first; --i)
    backward_row<K>(f.upper, f.kd, f.recip, X, i, last, width);
}

template <int K>
void substitute_block(const ScaledBand& f, double* X, const SparseDirectSolver::Block& b)
{
  switch (b.bandwidth)
  {
  case 0:
    return substitute<0, K>(f, X, b.first, b.last);
  case 1:
    return substitute<1, K>(f, X, b.first, b.last);
  case 2:
    return substitute<2, K>(f, X, b.first, b.last);
  case 3:
    return substitute<3, K>(f, X, b.first, b.last);
  case 4:
    return substitute<4, K>(f, X, b.first, b.last);
  default:
    return substitute<-1, K>(f, X, b.first, b.last, b.bandwidth);
  }
}

/// The largest |X| of each of the K interleaved columns over the rows [a, b).
template <int K>
void column_peaks(const double* X, const int a, const int b, double* peak)
{
  for (int r = 0; r < K; ++r)
    peak[r] = 0.;
  for (int i = a; i < b; ++i)
    for (int r = 0; r < K; ++r)
      peak[r] = std::max(peak[r], std::abs(X[i * K + r]));
}

/// True if every column's largest entry on a run is negligible against its peak.
template <int K>
bool negligible(const double* run_peak, const double* peak)
{
  for (int r = 0; r < K; ++r)
    if (run_peak[r] > SparseDirectSolver::local_tolerance * peak[r])
      return false;
  return true;
}

/// peak = max(peak, run_peak) column by column.
template <int K>
void raise_peaks(double* peak, const double* run_peak)
{
  for (int r = 0; r < K; ++r)
    peak[r] = std::max(peak[r], run_peak[r]);
}

/**
 * SparseDirectSolver::solve_local() on block @p b with half bandwidth KD
 * (1 to 4) for right-hand sides on its rows [s0, s1): the chains of
 * substitute(), started at s0 and stopped where a run of rows is negligible.
 * Returns the rows computed.
 */
template <int KD, int K>
RowRange substitute_local(const ScaledBand& f, double* __restrict X,
                          const SparseDirectSolver::Block& b, const int s0, const int s1)
{
  constexpr int run = SparseDirectSolver::local_run;
  double peak[K], run_peak[K];
  int end = b.last;
  ForwardChain<KD, K> forward{f, X, s0, b.last, {}};
  forward.start();
  column_peaks<K>(X, s0, std::min(b.last, s0 + KD), peak);
  for (int j = s0 + KD; j < b.last;)
  {
    const int from = j, stop = std::min(b.last, j + run);
    for (; j < stop; ++j)
      forward.step(j);
    column_peaks<K>(X, from, stop, run_peak);
    if (from >= s1 && stop - from == run && negligible<K>(run_peak, peak))
    {
      end = stop;
      break;
    }
    raise_peaks<K>(peak, run_peak);
  }
  BackwardChain<KD, K> backward{f, X, b.first, end, {}};
  backward.start();
  column_peaks<K>(X, std::max(b.first, end - KD), end, peak);
  int begin = b.first;
  for (int i = end - 1 - KD; i >= b.first;)
  {
    const int from = i, stop = std::max(b.first - 1, i - run);
    for (; i > stop; --i)
      backward.step(i);
    column_peaks<K>(X, stop + 1, from + 1, run_peak);
    if (from < s0 && from - stop == run && negligible<K>(run_peak, peak))
    {
      begin = stop + 1;
      break;
    }
    raise_peaks<K>(peak, run_peak);
  }
  return {begin, end};
}

/// substitute_local() for the block's bandwidth; a diagonal block on [s0, s1)
/// only, a wide one whole.
template <int K>
RowRange substitute_block_local(const ScaledBand& f, double* X,
                                const SparseDirectSolver::Block& b, const int s0,
                                const int s1)
{
  switch (b.bandwidth)
  {
  case 0:
    substitute<0, K>(f, X, s0, s1);
    return {s0, s1};
  case 1:
    return substitute_local<1, K>(f, X, b, s0, s1);
  case 2:
    return substitute_local<2, K>(f, X, b, s0, s1);
  case 3:
    return substitute_local<3, K>(f, X, b, s0, s1);
  case 4:
    return substitute_local<4, K>(f, X, b, s0, s1);
  default:
    substitute_block<K>(f, X, b);
    return {b.first, b.last};
  }
}
} // namespace

void SparseDirectSolver::find_blocks(const dealii::SparseMatrix<double>& A)
{
  // reach[i]: the largest column coupled to a row <= i; a block ends where
  // no row before the boundary reaches beyond it.
  independent_blocks.clear();
  Block current;
  int reach = -1;
  for (int i = 0; i < n; ++i)
  {
    for (auto it = A.begin(i); it != A.end(i); ++it)
      if (it->value() != 0.)
      {
        const int j = it->column();
        reach = std::max(reach, j);
        current.bandwidth = std::max(current.bandwidth, std::abs(i - j));
      }
    if (reach <= i)
    {
      current.last = i + 1;
      independent_blocks.push_back(current);
      current = Block{i + 1, i + 1, 0};
    }
  }
  // Merge neighbouring blocks of the same bandwidth (e.g. a diagonal stretch),
  // but keep long ones apart: solve_interleaved() substitutes two of them
  // side by side.
  std::vector<Block> merged;
  for (const Block& b : independent_blocks)
    if (!merged.empty() && merged.back().bandwidth == b.bandwidth &&
        (merged.back().last - merged.back().first < long_block ||
         b.last - b.first < long_block))
      merged.back().last = b.last;
    else
      merged.push_back(b);
  independent_blocks = std::move(merged);
}

bool SparseDirectSolver::try_banded_cholesky(const dealii::SparseMatrix<double>& A,
                                             const int max_bandwidth)
{
  n = A.m();
  kd = 0;
  // Row by row: a deal.II iterator's row() is a binary search.
  for (int i = 0; i < n; ++i)
    for (auto it = A.begin(i); it != A.end(i); ++it)
      if (it->value() != 0.)
      {
        kd = std::max(kd, std::abs(i - static_cast<int>(it->column())));
        if (kd > max_bandwidth)
          return false;
      }
  const int ld = kd + 1;
  // LAPACK upper band storage: U(i, j), i <= j <= i + kd, at (kd + i - j) + j ld;
  // the lower triangle, mirrored, at the same places to check the symmetry.
  std::vector<double> band(static_cast<std::size_t>(ld) * n, 0.), mirror(band.size(), 0.);
  for (int i = 0; i < n; ++i)
    for (auto it = A.begin(i); it != A.end(i); ++it)
    {
      const int j = it->column();
      if (std::abs(i - j) > kd)
        continue; // a stored zero outside the band
      if (i <= j)
        band[(kd + i - j) + static_cast<std::size_t>(j) * ld] = it->value();
      else
        mirror[(kd + j - i) + static_cast<std::size_t>(i) * ld] = it->value();
    }
  // Cholesky needs symmetry (up to round-off of the assembly).
  for (int j = 0; j < n; ++j)
    for (int i = std::max(0, j - kd); i < j; ++i)
    {
      const std::size_t e = (kd + i - j) + static_cast<std::size_t>(j) * ld;
      if (std::abs(band[e] - mirror[e]) >
          1e-12 * (std::abs(band[e]) + std::abs(mirror[e])))
        return false;
    }
  find_blocks(A); // the Cholesky factor has the block structure of A
  // A's band, for the twisted factors of the long blocks (if any).
  const bool any_long =
      std::any_of(independent_blocks.begin(), independent_blocks.end(),
                  [](const Block& b) { return b.last - b.first >= long_block; });
  const std::vector<double> matrix = any_long ? band : std::vector<double>();
  int info = 0;
  dpbtrf_("U", &n, &kd, band.data(), &ld, &info);
  if (info != 0) // not positive definite
    return false;
  reciprocal.resize(n);
  for (int i = 0; i < n; ++i)
    reciprocal[i] = 1. / band[kd + static_cast<std::size_t>(i) * ld];
  // U(i, j) at band[(kd + i - j) + j ld] over U(j, j) (forward) and over
  // U(i, i) (backward), at the same places.
  lower_scaled.assign(band.size(), 0.);
  upper_scaled.assign(band.size(), 0.);
  for (int j = 0; j < n; ++j)
    for (int i = std::max(0, j - kd); i < j; ++i)
    {
      const std::size_t e = (kd + i - j) + static_cast<std::size_t>(j) * ld;
      lower_scaled[e] = band[e] * reciprocal[j];
      upper_scaled[e] = band[e] * reciprocal[i];
    }
  twisted.assign(independent_blocks.size(), TwistedBand());
  for (std::size_t i = 0; i < independent_blocks.size(); ++i)
  {
    Block& b = independent_blocks[i];
    if (b.last - b.first >= long_block &&
        twisted[i].factorize(b.first, b.last, b.bandwidth, kd, matrix, band))
      b.twist = twisted[i].twist();
  }
  return true;
}

const char* to_string(const LinearSolverType type)
{
  switch (type)
  {
  case LinearSolverType::banded:
    return "banded";
  case LinearSolverType::umfpack:
    return "umfpack";
  case LinearSolverType::trilinos_klu:
    return "trilinos-klu";
  }
  return "";
}

struct SparseDirectSolver::Klu
{
  dealii::TrilinosWrappers::SparseMatrix matrix;
  dealii::SolverControl control;
  dealii::TrilinosWrappers::SolverDirect solver{
      control,
      dealii::TrilinosWrappers::SolverDirect::AdditionalData(false, "Amesos_Klu")};
  mutable dealii::LinearAlgebra::distributed::Vector<double> x, b;
};

SparseDirectSolver::SparseDirectSolver() = default;
SparseDirectSolver::~SparseDirectSolver() = default;

void SparseDirectSolver::factorize(const dealii::SparseMatrix<double>& matrix,
                                   const std::string& what, const LinearSolverType type,
                                   const int max_bandwidth)
{
  klu.reset();
  banded = type == LinearSolverType::banded && try_banded_cholesky(matrix, max_bandwidth);
  if (banded)
    return;
  n = matrix.m();
  lower_scaled.clear();
  upper_scaled.clear();
  independent_blocks.clear();
  twisted.clear();
  try
  {
    if (type == LinearSolverType::trilinos_klu)
    {
      klu = std::make_unique<Klu>();
      klu->matrix.reinit(matrix);
      klu->solver.initialize(klu->matrix);
      klu->x.reinit(n);
      klu->b.reinit(n);
    }
    else
      umfpack.initialize(matrix);
  }
  catch (const std::exception&)
  {
    throw SimulationError("the " + what + " is singular and cannot be factorised (" +
                          to_string(type) + ")");
  }
}

void SparseDirectSolver::solve_general(dealii::Vector<double>& x) const
{
  if (!klu)
  {
    umfpack.solve(x);
    return;
  }
  for (int i = 0; i < n; ++i)
    klu->b[i] = x[i];
  klu->solver.solve(klu->x, klu->b);
  for (int i = 0; i < n; ++i)
    x[i] = klu->x[i];
}

SparseDirectSolver::ScaledBand SparseDirectSolver::scaled_band() const
{
  return {lower_scaled.data(), upper_scaled.data(), reciprocal.data(), kd};
}

double SparseDirectSolver::twisted_record_fraction() const
{
  double records = 0., steps = 0.;
  for (const TwistedBand& t : twisted)
  {
    records += t.distinct_records();
    steps += t.substitution_steps();
  }
  return steps > 0. ? records / steps : 0.;
}

void SparseDirectSolver::solve(dealii::Vector<double>& x) const
{
  if (!banded)
    solve_general(x);
  else
    solve_interleaved(x.begin(), 1);
}

void SparseDirectSolver::solve_interleaved(double* X, const unsigned int k) const
{
  if (!banded)
  {
    dealii::Vector<double> column(n);
    for (unsigned int r = 0; r < k; ++r)
    {
      for (int i = 0; i < n; ++i)
        column[i] = X[i * k + r];
      solve_general(column);
      for (int i = 0; i < n; ++i)
        X[i * k + r] = column[i];
    }
    return;
  }
  const ScaledBand f = scaled_band();
  for (std::size_t i = 0; i < independent_blocks.size(); ++i)
  {
    const Block& b = independent_blocks[i];
    // One right-hand side: a long block's twisted factor, two such blocks
    // side by side (a section's contact wire and messenger: four chains).
    if (k == 1 && b.twist > 0)
    {
      if (i + 1 < independent_blocks.size() && independent_blocks[i + 1].twist > 0)
      {
        TwistedBand::solve_pair(twisted[i], twisted[i + 1], X);
        ++i;
      }
      else
        twisted[i].solve(X);
      continue;
    }
    switch (k)
    {
    case 1:
      substitute_block<1>(f, X, b);
      break;
    case 2:
      substitute_block<2>(f, X, b);
      break;
    case 3:
      substitute_block<3>(f, X, b);
      break;
    case 4:
      substitute_block<4>(f, X, b);
      break;
    default:
      AssertThrow(false,
                  dealii::ExcMessage("solve_interleaved: 1 to 4 right-hand sides"));
    }
  }
}

void SparseDirectSolver::solve_local(double* X, const unsigned int k,
                                     RowRanges& reach) const
{
  AssertThrow(k >= 1 && k <= 4,
              dealii::ExcMessage("solve_local: 1 to 4 right-hand sides"));
  if (!banded)
  {
    solve_interleaved(X, k);
    reach = {{0, n}};
    return;
  }
  const ScaledBand f = scaled_band();
  RowRanges computed;
  for (const Block& b : independent_blocks)
  {
    int s0 = b.last, s1 = b.first; // the rows of reach in b
    for (const RowRange& r : reach)
      if (r.first < b.last && r.last > b.first)
      {
        s0 = std::min(s0, std::max(r.first, b.first));
        s1 = std::max(s1, std::min(r.last, b.last));
      }
    if (s0 >= s1)
      continue;
    switch (k)
    {
    case 1:
      computed.push_back(substitute_block_local<1>(f, X, b, s0, s1));
      break;
    case 2:
      computed.push_back(substitute_block_local<2>(f, X, b, s0, s1));
      break;
    case 3:
      computed.push_back(substitute_block_local<3>(f, X, b, s0, s1));
      break;
    default:
      computed.push_back(substitute_block_local<4>(f, X, b, s0, s1));
    }
  }
  reach.swap(computed);
}
} // namespace pantocat
