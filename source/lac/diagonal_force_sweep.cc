#include <pantocat/lac/diagonal_force_sweep.h>
#include <pantocat/lac/repeating_rows.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>

namespace pantocat
{
ForceDiagonals::ForceDiagonals(const dealii::SparseMatrix<double>& K,
                               const dealii::SparseMatrix<double>& D)
{
  const unsigned int n = K.m();
  // Row by row: a deal.II iterator's row() is a binary search.
  for (unsigned int i = 0; i < n; ++i)
    for (auto it = K.begin(i); it != K.end(i); ++it)
      bandwidth = std::max(
          bandwidth, std::abs(static_cast<int>(i) - static_cast<int>(it->column())));
  const int b = bandwidth;
  stiffness.assign(2 * b + 1, std::vector<double>(n, 0.));
  half_damping.assign(2 * b + 1, std::vector<double>(n, 0.));
  std::vector<bool> k_used(2 * b + 1, false), d_used(2 * b + 1, false);
  for (unsigned int i = 0; i < n; ++i)
  {
    auto d = D.begin(i);
    for (auto k = K.begin(i); k != K.end(i); ++k, ++d)
    {
      const int o = static_cast<int>(k->column()) - static_cast<int>(i) + b;
      stiffness[o][i] = k->value();
      half_damping[o][i] = 0.5 * d->value();
      k_used[o] = k_used[o] || k->value() != 0.;
      d_used[o] = d_used[o] || d->value() != 0.;
    }
  }
  for (int o = 0; o <= 2 * b; ++o)
  {
    if (k_used[o])
      stiffness_offsets.push_back(o - b);
    if (d_used[o])
      damping_offsets.push_back(o - b);
  }
}

namespace
{
/// Rows of one block: they stay in the first-level cache while the offsets pass.
constexpr int rows_per_block = 512;

/// The operands of one block of rows [begin, end) and its band's reach.
struct Block
{
  int n, b, begin, end;
  const double* f;
  const double* __restrict q;
  double* __restrict out;
  const double* __restrict u; ///< v_{n-1} + v_n from row lo
  int lo;
};

/**
 * The block's rows from the diagonals: the first stiffness diagonal writes
 * f - K q where it reaches (f elsewhere), the others and the damping
 * diagonals subtract their terms. Compiled for AVX2 beside the baseline,
 * chosen when the program starts: a wider vector per instruction, the same
 * operations on each entry (no fused multiply-add), so the same bits.
 */
__attribute__((target_clones("avx2", "default"))) void
sweep_by_diagonals(const Block& x, const std::vector<int>& k_offsets,
                   const std::vector<std::vector<double>>& k,
                   const std::vector<int>& d_offsets,
                   const std::vector<std::vector<double>>& d)
{
  const int n = x.n, b = x.b, begin = x.begin, end = x.end;
  const double* __restrict f = x.f;
  const double* __restrict q = x.q;
  double* __restrict out = x.out;
  std::size_t next = 0;
  if (k_offsets.empty())
    std::copy(f + begin, f + end, out + begin);
  else
  {
    const int o = k_offsets[next++];
    const double* __restrict ko = k[o + b].data();
    const int first = std::min(end, std::max(begin, -o));
    const int last = std::max(first, std::min(end, n - o));
    std::copy(f + begin, f + first, out + begin);
    for (int i = first; i < last; ++i)
      out[i] = f[i] - ko[i] * q[i + o];
    std::copy(f + last, f + end, out + last);
  }
  for (; next < k_offsets.size(); ++next)
  {
    const int o = k_offsets[next];
    const double* __restrict ko = k[o + b].data();
    const int first = std::max(begin, -o), last = std::min(end, n - o);
    for (int i = first; i < last; ++i)
      out[i] -= ko[i] * q[i + o];
  }
  for (const int o : d_offsets)
  {
    const double* __restrict dd = d[o + b].data();
    const double* __restrict uo = x.u + o - x.lo;
    const int first = std::max(begin, -o), last = std::min(end, n - o);
    for (int i = first; i < last; ++i)
      out[i] -= dd[i] * uo[i];
  }
}

/**
 * The rows [@p begin, @p end) of a run, from its two rows' coefficients (@p
 * kc, @p dc: [offset index][parity], parity 0 at @p begin; every offset
 * reaches inside the matrix): eight rows at once in two independent
 * four-double vectors, so that two rows' chains of subtractions overlap,
 * each row's terms summed in a register until it is done (no partial sums
 * through memory). The velocity sums v_{n-1} + v_n are formed once per row,
 * a block of rows and its band's reach at a time into @p u (block + 2 b
 * entries, in the first-level cache), and each damping term reads them
 * there: one load per term instead of two loads and an addition. This takes
 * 0.77 to 0.98 of the time of the sweep before it (four rows at once,
 * velocity sums formed at every term), both timed in one program on 1500 to
 * 150 000 rows (doc/benchmarks.md, session 26). The terms, their order and
 * each operation are those of sweep_by_diagonals(), so the bits are the
 * same. Compiled for AVX2 beside the baseline (no fused multiply-add).
 */
__attribute__((target_clones("avx2", "default"))) void sweep_run(
    const int begin, const int end, const double* __restrict f,
    const double* __restrict q, const double* __restrict vp, const double* __restrict v,
    double* __restrict out, const std::vector<int>& k_offsets,
    const std::array<std::array<double, 2>, 7>& kc, const std::vector<int>& d_offsets,
    const std::array<std::array<double, 2>, 7>& dc, double* __restrict u)
{
  using Quad = double __attribute__((vector_size(32)));
  const auto load = [](const double* x)
  {
    Quad y;
    std::memcpy(&y, x, sizeof y);
    return y;
  };
  const int nk = k_offsets.size(), nd = d_offsets.size();
  int ko[7], dof[7];
  Quad kq[7], dq[7];
  for (int j = 0; j < nk; ++j)
  {
    ko[j] = k_offsets[j];
    kq[j] = Quad{kc[j][0], kc[j][1], kc[j][0], kc[j][1]};
  }
  int reach = 0; // the damping offsets lie in [-reach, reach]
  for (int j = 0; j < nd; ++j)
  {
    dof[j] = d_offsets[j];
    dq[j] = Quad{dc[j][0], dc[j][1], dc[j][0], dc[j][1]};
    reach = std::max(reach, std::abs(dof[j]));
  }
  // Blocks of an even number of rows: the parity of a row is its distance
  // from begin.
  for (int first = begin; first < end; first += rows_per_block)
  {
    const int last = std::min(end, first + rows_per_block);
    // u[j - first + reach] = v_{n-1} + v_n of row j.
    if (nd > 0)
      for (int j = first - reach; j < last + reach; ++j)
        u[j - first + reach] = vp[j] + v[j];
    const double* __restrict uu = u + reach; // row i at uu[i - first]
    int i = first;
    // Eight rows at once, two chains of subtractions side by side (each row's
    // terms still one after the other, in the offsets' order).
    for (; i + 8 <= last; i += 8)
    {
      Quad s0 = load(f + i), s1 = load(f + i + 4);
      for (int j = 0; j < nk; ++j)
      {
        s0 -= kq[j] * load(q + i + ko[j]);
        s1 -= kq[j] * load(q + i + 4 + ko[j]);
      }
      for (int j = 0; j < nd; ++j)
      {
        s0 -= dq[j] * load(uu + (i - first) + dof[j]);
        s1 -= dq[j] * load(uu + (i + 4 - first) + dof[j]);
      }
      std::memcpy(out + i, &s0, sizeof s0);
      std::memcpy(out + i + 4, &s1, sizeof s1);
    }
    for (; i < last; ++i) // the last rows of a run, fewer than eight
    {
      const int p = (i - begin) % 2;
      double s = f[i];
      for (int j = 0; j < nk; ++j)
        s -= kc[j][p] * q[i + ko[j]];
      for (int j = 0; j < nd; ++j)
        s -= dc[j][p] * uu[i - first + dof[j]];
      out[i] = s;
    }
  }
}
} // namespace

void DiagonalForceSweep::initialize(const int n_rows, const int bandwidth,
                                    const std::vector<int>& stiffness_offsets,
                                    const std::vector<std::vector<double>>& stiffness,
                                    const std::vector<int>& damping_offsets,
                                    const std::vector<std::vector<double>>& half_damping)
{
  n = n_rows;
  b = bandwidth;
  k_offsets = &stiffness_offsets;
  k = &stiffness;
  d_offsets = &damping_offsets;
  d = &half_damping;
  velocity_sum.assign(rows_per_block + 2 * b, 0.);
  find_runs();
  group_exceptions();
}

bool DiagonalForceSweep::same_coefficients(const int i, const int j) const
{
  for (const int o : *k_offsets)
    if ((*k)[o + b][i] != (*k)[o + b][j])
      return false;
  for (const int o : *d_offsets)
    if ((*d)[o + b][i] != (*d)[o + b][j])
      return false;
  return true;
}

void DiagonalForceSweep::find_runs()
{
  runs.clear();
  exceptions.clear();
  exception_coefficients.clear();
  // The coefficients kept aside: at most 7 offsets of each operator.
  if (b > 3 || k_offsets->size() > 7 || d_offsets->size() > 7)
    return;
  // Rows whose every offset reaches inside the matrix: [b, n - b).
  const auto always = [](int) { return true; };
  for (const RepeatingRows& found : find_repeating_rows(
           b, n - b, minimum_run, always, always,
           [&](const int i, const int j) { return same_coefficients(i, j); }))
  {
    const int start = found.first;
    Run r;
    r.first = start;
    r.last = found.last;
    for (std::size_t j = 0; j < k_offsets->size(); ++j)
      for (int p = 0; p < 2; ++p)
        r.k[j][p] = (*k)[(*k_offsets)[j] + b][start + p];
    for (std::size_t j = 0; j < d_offsets->size(); ++j)
      for (int p = 0; p < 2; ++p)
        r.d[j][p] = (*d)[(*d_offsets)[j] + b][start + p];
    r.first_exception = exceptions.size();
    for (const int i : found.exceptions)
    {
      exceptions.push_back(i);
      for (const int o : *k_offsets)
        exception_coefficients.push_back((*k)[o + b][i]);
      for (const int o : *d_offsets)
        exception_coefficients.push_back((*d)[o + b][i]);
    }
    r.last_exception = exceptions.size();
    runs.push_back(r);
  }
}

namespace
{
/**
 * The exceptions four at a time, one row per lane (@p rows: four per group,
 * the last group padded with its last row), from their coefficients laid
 * out [group][term][lane]: the terms of sweep_by_diagonals() for an inner
 * row, in its order, each lane's operations those of a row swept alone. Four
 * rows' chains of subtractions advance together instead of one after the
 * other (a row alone waits on its 14 dependent subtractions).
 */
__attribute__((target_clones("avx2", "default"))) void
sweep_exception_groups(const int* rows, const std::size_t groups, const double* c,
                       const std::vector<int>& k_offsets,
                       const std::vector<int>& d_offsets, const double* f,
                       const double* q, const double* vp, const double* v, double* out)
{
  using Quad = double __attribute__((vector_size(32)));
  for (std::size_t g = 0; g < groups; ++g, rows += 4)
  {
    const int r0 = rows[0], r1 = rows[1], r2 = rows[2], r3 = rows[3];
    Quad s = {f[r0], f[r1], f[r2], f[r3]};
    for (const int o : k_offsets)
    {
      Quad coefficient;
      std::memcpy(&coefficient, c, sizeof coefficient);
      c += 4;
      s -= coefficient * Quad{q[r0 + o], q[r1 + o], q[r2 + o], q[r3 + o]};
    }
    for (const int o : d_offsets)
    {
      Quad coefficient;
      std::memcpy(&coefficient, c, sizeof coefficient);
      c += 4;
      s -= coefficient * Quad{vp[r0 + o] + v[r0 + o], vp[r1 + o] + v[r1 + o],
                              vp[r2 + o] + v[r2 + o], vp[r3 + o] + v[r3 + o]};
    }
    // In reverse: a padded group's repeated last row gets its value last.
    out[r3] = s[3];
    out[r2] = s[2];
    out[r1] = s[1];
    out[r0] = s[0];
  }
}
} // namespace

void DiagonalForceSweep::group_exceptions()
{
  // [group][term][lane]: the coefficients of exceptions 4 g .. 4 g + 3 (the
  // last group repeats its last exception).
  const std::size_t terms = k_offsets->size() + d_offsets->size();
  const std::size_t groups = (exceptions.size() + 3) / 4;
  grouped_rows.assign(4 * groups, 0);
  grouped_coefficients.assign(4 * groups * terms, 0.);
  for (std::size_t g = 0; g < groups; ++g)
    for (std::size_t lane = 0; lane < 4; ++lane)
    {
      const std::size_t e = std::min(4 * g + lane, exceptions.size() - 1);
      grouped_rows[4 * g + lane] = exceptions[e];
      for (std::size_t t = 0; t < terms; ++t)
        grouped_coefficients[(g * terms + t) * 4 + lane] =
            exception_coefficients[e * terms + t];
    }
}

int DiagonalForceSweep::rows_in_runs() const
{
  int rows = 0;
  for (const Run& r : runs)
    rows += r.last - r.first - (r.last_exception - r.first_exception);
  return rows;
}

void DiagonalForceSweep::apply(const double* f, const double* q, const double* vp,
                               const double* v, double* out)
{
  double* __restrict u = velocity_sum.data();
  const auto sweep = [&](const int first, const int last)
  {
    for (int begin = first; begin < last; begin += rows_per_block)
    {
      Block x{n, b, begin, std::min(last, begin + rows_per_block), f, q, out, u, 0};
      if (!d_offsets->empty())
      {
        // v_{n-1} + v_n once per row of the block and its band's reach.
        x.lo = std::max(0, begin - b);
        const int hi = std::min(n, x.end + b);
        for (int j = x.lo; j < hi; ++j)
          u[j - x.lo] = vp[j] + v[j];
      }
      sweep_by_diagonals(x, *k_offsets, *k, *d_offsets, *d);
    }
  };
  int row = 0;
  for (const Run& r : runs)
  {
    sweep(row, r.first);
    sweep_run(r.first, r.last, f, q, vp, v, out, *k_offsets, r.k, *d_offsets, r.d, u);
    row = r.last;
  }
  sweep(row, n);
  // The runs' exceptions, over what their runs gave them.
  sweep_exception_groups(grouped_rows.data(), grouped_rows.size() / 4,
                         grouped_coefficients.data(), *k_offsets, *d_offsets, f, q, vp, v,
                         out);
}
} // namespace pantocat
