#include <pantocat/lac/twisted_band.h>

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <type_traits>

extern "C"
{
  // LAPACK: Cholesky factorisation of a symmetric positive definite band matrix.
  void dpbtrf_(const char* uplo, const int* n, const int* kd, double* ab, const int* ldab,
               int* info);
  // LAPACK: Cholesky factorisation of a symmetric positive definite matrix.
  void dpotrf_(const char* uplo, const int* n, double* a, const int* lda, int* info);
}

namespace pantocat
{
namespace
{
/// Two doubles in one SSE2 register (GCC's vector extension).
using Pair = TwistedBand::Pair;

/**
 * Two chains of a twisted substitution in one pair of doubles: the top's
 * rows (lane 0, direction Dir) and the bottom's (lane 1, direction -Dir),
 * each x_i = x_i / R(i, i) - sum_m (R(i, i -+ m) / R(i, i)) x_{i -+ m} over
 * the KD rows it took last (m = KD, ..., 1, the row just before last, as the
 * plain substitutions of SparseDirectSolver), kept in registers (w[m - 1]).
 * The records hold both lanes' coefficients side by side, so one vector
 * operation does a step of both chains: the same operations on each lane,
 * in the same order, as a scalar step.
 */
template <int KD, int Dir>
struct PairedLane
{
  const Pair* records;
  const unsigned int* at; ///< the next step's record: records + *at
  double* top;
  double* bottom;
  int length;
  Pair w[KD];

  [[gnu::always_inline]] void step()
  {
    const Pair* record = records + *at;
    const Pair x = {*top, *bottom};
    Pair s = x * record[0];
    for (int m = KD; m >= 1; --m)
      s -= record[1 + KD - m] * w[m - 1];
    *top = s[0];
    *bottom = s[1];
    for (int m = KD - 1; m >= 1; --m)
      w[m] = w[m - 1];
    w[0] = s;
    top += Dir;
    bottom -= Dir;
    ++at;
  }
};

/// A paired lane on @p records from the rows @p top and @p bottom, its window
/// on the KD rows before them in their directions: zeros (the chains' first
/// rows have zero coefficients beyond the block) or @p x's values.
template <int KD, int Dir>
PairedLane<KD, Dir> lane(const std::vector<Pair>& records,
                         const std::vector<unsigned int>& at, double* x, const int top,
                         const int bottom, const int length, const bool window_from_x)
{
  PairedLane<KD, Dir> l{records.data(), at.data(), x + top, x + bottom, length, {}};
  if (window_from_x)
    for (int m = 1; m <= KD; ++m)
      l.w[m - 1] = Pair{x[top - Dir * m], x[bottom + Dir * m]};
  return l;
}

/**
 * Independent chains side by side: a step of each in the same iteration.
 * The recurrences are latency-bound (each row waits for the one before), so
 * a few chains in flight take about the time of one.
 */
template <typename... Lanes>
void side_by_side(Lanes&... lanes)
{
  const int common = std::min({lanes.length...});
  for (int t = 0; t < common; ++t)
    (lanes.step(), ...);
  const int end = std::max({lanes.length...});
  for (int t = common; t < end; ++t)
    ((t < lanes.length ? lanes.step() : void()), ...);
}

/**
 * Keeps each of the @p steps records of @p size pairs in @p records once:
 * a record equal, to the bit, to that of one of the four steps before (a
 * uniform grid's factor settles to rows that repeat with period 1, 2 or 4)
 * takes that step's place. Returns where each step's record starts.
 */
std::vector<unsigned int> store_distinct(std::vector<Pair>& records, const int steps,
                                         const int size)
{
  std::vector<unsigned int> at(steps);
  std::vector<Pair> distinct;
  const auto same = [&](const Pair* a, const Pair* b)
  { return std::memcmp(a, b, sizeof(Pair) * size) == 0; };
  for (int s = 0; s < steps; ++s)
  {
    const Pair* record = records.data() + static_cast<std::size_t>(s) * size;
    int found = -1;
    for (int p = 1; p <= 4 && p <= s && found < 0; ++p)
      if (same(distinct.data() + at[s - p], record))
        found = static_cast<int>(at[s - p]);
    if (found >= 0)
      at[s] = found;
    else
    {
      at[s] = distinct.size();
      distinct.insert(distinct.end(), record, record + size);
    }
  }
  distinct.shrink_to_fit();
  records.swap(distinct);
  return at;
}

/// body(std::integral_constant<int, bw>{}) for a half bandwidth 1 to 4.
template <typename Body>
void with_bandwidth(const int bw, const Body& body)
{
  switch (bw)
  {
  case 1:
    return body(std::integral_constant<int, 1>{});
  case 2:
    return body(std::integral_constant<int, 2>{});
  case 3:
    return body(std::integral_constant<int, 3>{});
  default:
    return body(std::integral_constant<int, 4>{});
  }
}
} // namespace

bool TwistedBand::factorize(const int first_row, const int last_row, const int bandwidth,
                            const int kd, const std::vector<double>& matrix,
                            const std::vector<double>& factor)
{
  *this = TwistedBand();
  const int KD = bandwidth;
  if (KD < 1 || KD > max_bandwidth || kd < KD || last_row - first_row < 4 * KD)
    return false;
  // KD or KD + 1 middle rows, so that the top and the bottom have the same
  // number of rows (the middle may be wider than KD: top and bottom stay apart).
  const int middle_rows = KD + (last_row - first_row - KD) % 2;
  const int half = (last_row - first_row - middle_rows) / 2;
  const int ld = kd + 1, twist = first_row + half, middle_end = twist + middle_rows;
  const auto at = [kd, ld](const int i, const int j) // i <= j
  { return (kd + i - j) + static_cast<std::size_t>(j) * ld; };

  // The rows [twist, last) in reverse order (row i at last - 1 - i), factorised.
  int rows = last_row - twist, rkd = KD, rld = KD + 1, info = 0;
  const auto reversed_at = [&](const int i, const int j) // i <= j
  {
    const int p = last_row - 1 - j, q = last_row - 1 - i;
    return (rkd + p - q) + static_cast<std::size_t>(q) * rld;
  };
  std::vector<double> reversed(static_cast<std::size_t>(rld) * rows, 0.);
  for (int j = twist; j < last_row; ++j)
    for (int i = std::max(twist, j - KD); i <= j; ++i)
      reversed[reversed_at(i, j)] = matrix[at(i, j)];
  dpbtrf_("U", &rows, &rkd, reversed.data(), &rld, &info);
  if (info != 0)
    return false;

  // The middle: the Cholesky factor of A_MM - C_T^T C_T - C_B^T C_B.
  double S[(max_bandwidth + 1) * (max_bandwidth + 1)] = {};
  for (int j = twist; j < middle_end; ++j)
    for (int i = std::max(twist, j - KD); i <= j; ++i)
    {
      double s = matrix[at(i, j)];
      for (int k = std::max(first_row, j - KD); k < twist; ++k)
        s -= factor[at(k, i)] * factor[at(k, j)];
      for (int k = middle_end; k <= std::min(last_row - 1, i + KD); ++k)
        s -= reversed[reversed_at(i, k)] * reversed[reversed_at(j, k)];
      S[(i - twist) + (j - twist) * middle_rows] = s;
    }
  int order = middle_rows;
  dpotrf_("U", &order, S, &order, &info);
  if (info != 0)
    return false;

  // R(i, j), i <= j, both in the block and at most KD apart.
  const auto R = [&](const int i, const int j)
  {
    if (i < twist)
      return factor[at(i, j)];
    if (j >= middle_end)
      return reversed[reversed_at(i, j)];
    return S[(i - twist) + (j - twist) * middle_rows];
  };
  const auto coefficient = [&](const int row, const int other, const double d)
  {
    if (other < first_row || other >= last_row)
      return 0.;
    return (other < row ? R(other, row) : R(row, other)) * d;
  };
  // The records of a paired lane's step: 1 / R(i, i), then the KD rows before
  // i in the chain's direction (rows i - dir m, m = KD, ..., 1), for the
  // top's row and the bottom's.
  const auto add_record =
      [&](std::vector<Pair>& records, const int top, const int bottom, const int dir)
  {
    const double d_top = 1. / R(top, top), d_bottom = 1. / R(bottom, bottom);
    records.push_back(Pair{d_top, d_bottom});
    for (int m = KD; m >= 1; --m)
      records.push_back(Pair{coefficient(top, top - dir * m, d_top),
                             coefficient(bottom, bottom + dir * m, d_bottom)});
  };
  first = first_row;
  t = twist;
  middle_size = middle_rows;
  kd_block = KD;
  rows_per_lane = half;
  forward.reserve(static_cast<std::size_t>(half) * (KD + 1));
  backward.reserve(forward.capacity());
  middle.reserve(static_cast<std::size_t>(middle_rows) * (1 + 3 * KD));
  for (int s = 0; s < half; ++s) // R^T y = b: the top down, the bottom up
    add_record(forward, first_row + s, last_row - 1 - s, +1);
  for (int s = 0; s < half; ++s) // R x = y: the top up, the bottom down
    add_record(backward, twist - 1 - s, middle_end + s, -1);
  forward_at = store_distinct(forward, half, KD + 1);
  backward_at = store_distinct(backward, half, KD + 1);
  for (int j = twist; j < middle_end; ++j)
  {
    const double d = 1. / R(j, j);
    middle.push_back(d);
    for (int m = KD; m >= 1; --m)
      middle.push_back(coefficient(j, j - m, d));
    for (int m = 1; m <= KD; ++m)
      middle.push_back(j + m >= middle_end ? coefficient(j, j + m, d) : 0.);
    for (int m = 1; m <= KD; ++m)
      middle.push_back(j + m < middle_end ? coefficient(j, j + m, d) : 0.);
  }
  return true;
}

template <int KD>
void TwistedBand::substitute_middle(double* x) const
{
  const int end = t + middle_size;
  const auto record = [&](const int j) { return middle.data() + (j - t) * (1 + 3 * KD); };
  // The rest of R^T y = b: the top's and the middle's rows before, the bottom's after.
  for (int j = t; j < end; ++j)
  {
    const double* r = record(j);
    double s = x[j] * r[0];
    for (int m = KD; m >= 1; --m)
      s -= r[1 + KD - m] * x[j - m];
    for (int m = std::max(1, end - j); m <= KD; ++m)
      s -= r[KD + m] * x[j + m];
    x[j] = s;
  }
  // R x = y: the middle rows are R's last.
  for (int i = end - 1; i >= t; --i)
  {
    const double* r = record(i);
    double s = x[i] * r[0];
    for (int m = 1; m <= KD && i + m < end; ++m)
      s -= r[2 * KD + m] * x[i + m];
    x[i] = s;
  }
}

template <int KA, int KB>
void TwistedBand::substitute(const TwistedBand& a, const TwistedBand* b, double* x)
{
  // R^T y = b towards the middles.
  {
    auto in_a =
        lane<KA, +1>(a.forward, a.forward_at, x, a.first,
                     a.t + a.middle_size + a.rows_per_lane - 1, a.rows_per_lane, false);
    if constexpr (KB > 0)
    {
      auto in_b = lane<KB, +1>(b->forward, b->forward_at, x, b->first,
                               b->t + b->middle_size + b->rows_per_lane - 1,
                               b->rows_per_lane, false);
      side_by_side(in_a, in_b);
    }
    else
      side_by_side(in_a);
  }
  a.substitute_middle<KA>(x);
  if constexpr (KB > 0)
    b->substitute_middle<KB>(x);
  // R x = y from the middles outwards.
  auto out_a = lane<KA, -1>(a.backward, a.backward_at, x, a.t - 1, a.t + a.middle_size,
                            a.rows_per_lane, true);
  if constexpr (KB > 0)
  {
    auto out_b = lane<KB, -1>(b->backward, b->backward_at, x, b->t - 1,
                              b->t + b->middle_size, b->rows_per_lane, true);
    side_by_side(out_a, out_b);
  }
  else
    side_by_side(out_a);
}
void TwistedBand::solve(double* x) const
{
  with_bandwidth(kd_block, [&](auto KA) { substitute<KA, 0>(*this, nullptr, x); });
}

void TwistedBand::solve_pair(const TwistedBand& a, const TwistedBand& b, double* x)
{
  with_bandwidth(
      a.kd_block, [&](auto KA)
      { with_bandwidth(b.kd_block, [&](auto KB) { substitute<KA, KB>(a, &b, x); }); });
}
} // namespace pantocat
