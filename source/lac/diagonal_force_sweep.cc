#include <pantocat/lac/diagonal_force_sweep.h>

#include <algorithm>
#include <cstdlib>

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
constexpr int block = 512;

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
 * The block's rows of a run, from its two rows' coefficients (@p kc, @p dc:
 * [offset index][parity]; the block starts at an even distance from the
 * run's first row, and every offset reaches inside the matrix). The terms
 * and their order are those of sweep_by_diagonals().
 */
__attribute__((target_clones("avx2", "default"))) void
sweep_run(const Block& x, const std::vector<int>& k_offsets,
          const std::array<std::array<double, 2>, 7>& kc,
          const std::vector<int>& d_offsets,
          const std::array<std::array<double, 2>, 7>& dc)
{
  const int begin = x.begin, end = x.end;
  const double* __restrict f = x.f;
  const double* __restrict q = x.q;
  double* __restrict out = x.out;
  const int pairs_end = begin + (end - begin) / 2 * 2;
  std::size_t next = 0;
  if (k_offsets.empty())
    std::copy(f + begin, f + end, out + begin);
  else
  {
    const int o = k_offsets[next];
    const double c0 = kc[next][0], c1 = kc[next][1];
    ++next;
    for (int i = begin; i < pairs_end; i += 2)
    {
      out[i] = f[i] - c0 * q[i + o];
      out[i + 1] = f[i + 1] - c1 * q[i + 1 + o];
    }
    if (pairs_end < end)
      out[pairs_end] = f[pairs_end] - c0 * q[pairs_end + o];
  }
  for (; next < k_offsets.size(); ++next)
  {
    const int o = k_offsets[next];
    const double c0 = kc[next][0], c1 = kc[next][1];
    for (int i = begin; i < pairs_end; i += 2)
    {
      out[i] -= c0 * q[i + o];
      out[i + 1] -= c1 * q[i + 1 + o];
    }
    if (pairs_end < end)
      out[pairs_end] -= c0 * q[pairs_end + o];
  }
  for (std::size_t j = 0; j < d_offsets.size(); ++j)
  {
    const int o = d_offsets[j];
    const double c0 = dc[j][0], c1 = dc[j][1];
    const double* __restrict uo = x.u + o - x.lo;
    for (int i = begin; i < pairs_end; i += 2)
    {
      out[i] -= c0 * uo[i];
      out[i + 1] -= c1 * uo[i + 1];
    }
    if (pairs_end < end)
      out[pairs_end] -= c0 * uo[pairs_end];
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
  velocity_sum.assign(block + 2 * b, 0.);
  find_runs();
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
  // Rows whose every offset reaches inside the matrix: [b, n - b). A run
  // takes the coefficients of its first two rows; rows with others (a point
  // mass, a support) are its exceptions. The scan of a run ends where more
  // than gap_limit exceptions follow each other (the run ends at its last
  // row with the pattern) or where they become more than one in eight. A
  // run is kept if it has at least minimum_run rows and at most one in four
  // exceptions, which every scan longer than minimum_run + gap_limit meets:
  // a start without a run costs O(minimum_run), and the scans stay linear in n.
  constexpr int gap_limit = 8;
  int start = b;
  std::vector<int> own;
  while (start + 2 <= n - b)
  {
    int last_match = start + 1, gap = 0;
    own.clear();
    for (int i = start + 2; i < n - b && gap <= gap_limit; ++i)
    {
      if (same_coefficients(i, start + (i - start) % 2))
        last_match = i, gap = 0;
      else
      {
        ++gap;
        own.push_back(i);
      }
      if (i - start >= minimum_run &&
          8 * own.size() > static_cast<std::size_t>(i - start))
        break;
    }
    const int end = last_match + 1;
    while (!own.empty() && own.back() >= end) // the rows after the last match
      own.pop_back();
    if (end - start < minimum_run ||
        4 * own.size() > static_cast<std::size_t>(end - start))
    {
      ++start;
      continue;
    }
    Run r;
    r.first = start;
    r.last = end;
    for (std::size_t j = 0; j < k_offsets->size(); ++j)
      for (int p = 0; p < 2; ++p)
        r.k[j][p] = (*k)[(*k_offsets)[j] + b][start + p];
    for (std::size_t j = 0; j < d_offsets->size(); ++j)
      for (int p = 0; p < 2; ++p)
        r.d[j][p] = (*d)[(*d_offsets)[j] + b][start + p];
    r.first_exception = exceptions.size();
    for (const int i : own)
    {
      exceptions.push_back(i);
      for (const int o : *k_offsets)
        exception_coefficients.push_back((*k)[o + b][i]);
      for (const int o : *d_offsets)
        exception_coefficients.push_back((*d)[o + b][i]);
    }
    r.last_exception = exceptions.size();
    runs.push_back(r);
    start = end;
  }
}

void DiagonalForceSweep::sweep_exception(const std::size_t e, const double* f,
                                         const double* q, const double* vp,
                                         const double* v, double* out) const
{
  // The terms of sweep_by_diagonals() for an inner row, in its order, from
  // the row's coefficients copied side by side (the diagonals are not read
  // in a step that sweeps runs: they would be fetched from memory).
  const int i = exceptions[e];
  const double* c =
      exception_coefficients.data() + e * (k_offsets->size() + d_offsets->size());
  double s = f[i];
  for (const int o : *k_offsets)
    s -= *c++ * q[i + o];
  for (const int o : *d_offsets)
    s -= *c++ * (vp[i + o] + v[i + o]);
  out[i] = s;
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
  const auto sweep = [&](const int first, const int last, const Run* run)
  {
    for (int begin = first; begin < last; begin += block)
    {
      Block x{n, b, begin, std::min(last, begin + block), f, q, out, u, 0};
      if (!d_offsets->empty())
      {
        // v_{n-1} + v_n once per row of the block and its band's reach.
        x.lo = std::max(0, begin - b);
        const int hi = std::min(n, x.end + b);
        for (int j = x.lo; j < hi; ++j)
          u[j - x.lo] = vp[j] + v[j];
      }
      if (run)
        sweep_run(x, *k_offsets, run->k, *d_offsets, run->d);
      else
        sweep_by_diagonals(x, *k_offsets, *k, *d_offsets, *d);
    }
  };
  int row = 0;
  for (const Run& r : runs)
  {
    sweep(row, r.first, nullptr);
    sweep(r.first, r.last, &r);
    for (std::size_t e = r.first_exception; e < r.last_exception; ++e)
      sweep_exception(e, f, q, vp, v, out);
    row = r.last;
  }
  sweep(row, n, nullptr);
}
} // namespace pantocat
