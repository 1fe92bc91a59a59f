#include <pantocat/lac/repeating_rows.h>
#include <pantocat/system/pattern_operators.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <tuple>
#include <type_traits>

namespace pantocat
{
PatternOperators::PatternOperators(const SemiDiscreteSystem& system)
    : system(system), load(system.load)
{
  block_shifts.push_back(Shift{0, system.n_dofs(), 0., 0.});
  build();
}

PatternOperators::PatternOperators(const SemiDiscreteSystem& system,
                                   const IterationFactors& s)
    : system(system), split(true), factors(s), load(system.load)
{
  split_damping(s);
  build();
}

namespace
{
/// Relative size below which an entry of E = D - mu M - gamma S is round-off.
constexpr double split_tolerance = 1e-12;

/// The terms of E_ij = D_ij - mu M_ij - gamma S_ij, S_ij formed as
/// assemble_iteration_matrix() forms it (K, then + s_D D, then + s_M M).
struct SplitTerms
{
  double e, scale; ///< E_ij, and |D_ij| + |mu M_ij| + |gamma S_ij|
};
SplitTerms split_terms(const PatternOperators::IterationFactors& s, const double mu,
                       const double gamma, const double m, const double d, const double k)
{
  const double s_ij = (k + s.damping * d) + s.mass * m;
  return {d - mu * m - gamma * s_ij,
          std::abs(d) + std::abs(mu * m) + std::abs(gamma * s_ij)};
}

/// E's entries of row @p i (in the pattern's order), 0 where one is
/// round-off: below split_tolerance of the largest terms of the row (an
/// entry that assembly cancels to round-off, as a Hermite node's value-slope
/// mass, is round-off in M and D alike).
std::vector<double> split_row(const SemiDiscreteSystem& sys,
                              const PatternOperators::IterationFactors& s,
                              const double mu, const double gamma, const unsigned int i)
{
  std::vector<double> e;
  double scale = 0.;
  auto d = sys.damping.begin(i), k = sys.stiffness.begin(i);
  for (auto m = sys.mass.begin(i); m != sys.mass.end(i); ++m, ++d, ++k)
  {
    const SplitTerms t = split_terms(s, mu, gamma, m->value(), d->value(), k->value());
    e.push_back(t.e);
    scale = std::max(scale, t.scale);
  }
  for (double& x : e)
    if (std::abs(x) <= split_tolerance * scale)
      x = 0.;
  return e;
}

/// mu and gamma of D = alpha M + beta K for the factors @p s (class comment).
std::pair<double, double> shift_factors(const PatternOperators::IterationFactors& s,
                                        const double alpha, const double beta)
{
  const double gamma = beta / (s.stiffness + s.damping * beta);
  return {alpha - gamma * (s.mass + s.damping * alpha), gamma};
}
} // namespace

const PatternOperators::Shift& PatternOperators::shift_of(const unsigned int i) const
{
  const auto at = std::upper_bound(block_shifts.begin(), block_shifts.end(), i,
                                   [](const unsigned int row, const Shift& b)
                                   { return row < b.first; });
  return *(at - 1);
}

std::vector<double> PatternOperators::damping_row(const unsigned int i) const
{
  const Shift& shift = shift_of(i);
  if (split && (shift.mu != 0. || shift.gamma != 0.))
    return split_row(system, factors, shift.mu, shift.gamma, i);
  std::vector<double> d;
  for (auto e = system.damping.begin(i); e != system.damping.end(i); ++e)
    d.push_back(e->value());
  return d;
}

void PatternOperators::split_damping(const IterationFactors& s)
{
  const SemiDiscreteSystem& sys = system;
  // Rows of a block that break the law D = alpha M + beta K (E not zero).
  const auto breaking_rows = [&](const DofBlock& b, const double alpha, const double beta)
  {
    const auto [mu, gamma] = shift_factors(s, alpha, beta);
    unsigned int rows = 0;
    for (unsigned int i = b.first; i < b.first + b.size; ++i)
    {
      const std::vector<double> e = split_row(sys, s, mu, gamma, i);
      rows += std::any_of(e.begin(), e.end(), [](const double x) { return x != 0.; });
    }
    return rows;
  };
  // The laws that fit a row's entries exactly: beta = 0 first (viscous
  // damping), then alpha and beta by least squares.
  const auto fits = [&](const unsigned int i, const double alpha, const double beta)
  {
    double scale = 0., worst = 0.;
    auto d = sys.damping.begin(i), k = sys.stiffness.begin(i);
    for (auto m = sys.mass.begin(i); m != sys.mass.end(i); ++m, ++d, ++k)
    {
      worst =
          std::max(worst, std::abs(d->value() - alpha * m->value() - beta * k->value()));
      scale = std::max(scale, std::abs(d->value()) + std::abs(alpha * m->value()) +
                                  std::abs(beta * k->value()));
    }
    return worst <= split_tolerance * scale;
  };
  const auto law_of_row =
      [&](const unsigned int i) -> std::optional<std::pair<double, double>>
  {
    double mm = 0., mk = 0., kk = 0., dm = 0., dk = 0.;
    unsigned int entries = 0;
    auto d = sys.damping.begin(i), k = sys.stiffness.begin(i);
    for (auto m = sys.mass.begin(i); m != sys.mass.end(i); ++m, ++d, ++k, ++entries)
    {
      mm += m->value() * m->value();
      mk += m->value() * k->value();
      kk += k->value() * k->value();
      dm += d->value() * m->value();
      dk += d->value() * k->value();
    }
    if (entries < 2 || mm == 0.)
      return std::nullopt;
    if (fits(i, dm / mm, 0.))
      return std::make_pair(dm / mm, 0.);
    const double det = mm * kk - mk * mk;
    if (!(std::abs(det) > 1e-8 * mm * kk))
      return std::nullopt;
    const double alpha = (dm * kk - dk * mk) / det, beta = (dk * mm - dm * mk) / det;
    if (fits(i, alpha, beta))
      return std::make_pair(alpha, beta);
    return std::nullopt;
  };
  for (const DofBlock& b : sys.blocks)
  {
    Shift shift{b.first, b.first + b.size, 0., 0.};
    if (b.size >= minimum_stretch)
    {
      // Candidate laws from the block's rows (distinct ones, at most 4); the
      // one that fewest rows break, if fewer than half of them do.
      std::vector<std::pair<double, double>> laws;
      for (unsigned int i = b.first; i < b.first + b.size && laws.size() < 4; ++i)
        if (const auto law = law_of_row(i))
          if (std::none_of(laws.begin(), laws.end(),
                           [&](const auto& l) { return fits(i, l.first, l.second); }))
            laws.push_back(*law);
      unsigned int fewest = (b.size + 1) / 2;
      for (const auto& [alpha, beta] : laws)
        if (const unsigned int rows = breaking_rows(b, alpha, beta); rows < fewest)
        {
          fewest = rows;
          std::tie(shift.mu, shift.gamma) = shift_factors(s, alpha, beta);
        }
    }
    block_shifts.push_back(shift);
  }
  // Blocks that do not tile the rows in order (a system built without them):
  // no split, D on every row.
  bool tiled = !block_shifts.empty() && block_shifts.front().first == 0 &&
               block_shifts.back().last == sys.n_dofs();
  for (std::size_t b = 1; b < block_shifts.size(); ++b)
    tiled = tiled && block_shifts[b].first == block_shifts[b - 1].last;
  if (!tiled)
    block_shifts.assign(1, Shift{0, sys.n_dofs(), 0., 0.});
}

void PatternOperators::build()
{
  const unsigned int n = system.n_dofs();
  // Each row's offsets j - i in the pattern's order; consecutive rows with
  // the same ones form a run.
  std::vector<std::vector<int>> row_offsets(n);
  for (unsigned int i = 0; i < n; ++i)
    for (auto m = system.mass.begin(i); m != system.mass.end(i); ++m)
      row_offsets[i].push_back(static_cast<int>(m->column()) - static_cast<int>(i));
  // Runs, row by row: the stride (1, 2 or 3) whose rows with the same
  // offsets reach furthest.
  std::vector<char> taken(n, 0);
  for (unsigned int i = 0; i < n; ++i)
  {
    if (taken[i])
      continue;
    const auto length = [&](const unsigned int stride)
    {
      unsigned int rows = 1;
      for (unsigned int j = i + stride;
           j < n && !taken[j] && row_offsets[j] == row_offsets[i]; j += stride)
        ++rows;
      return rows;
    };
    unsigned int stride = 1, rows = length(1);
    for (const unsigned int s : {2u, 3u})
      if (const unsigned int l = length(s); l > rows)
        stride = s, rows = l;
    Run run{i,
            stride,
            rows,
            static_cast<unsigned int>(offsets.size()),
            static_cast<unsigned int>(row_offsets[i].size()),
            mass.size()};
    offsets.insert(offsets.end(), row_offsets[i].begin(), row_offsets[i].end());
    const std::size_t size = static_cast<std::size_t>(run.rows) * run.n_offsets;
    mass.resize(mass.size() + size);
    damping.resize(damping.size() + size);
    stiffness.resize(stiffness.size() + size);
    for (unsigned int r = 0; r < run.rows; ++r)
    {
      const unsigned int row = i + r * stride;
      taken[row] = 1;
      const std::vector<double> d = damping_row(row);
      auto k = system.stiffness.begin(row);
      unsigned int e = 0;
      for (auto m = system.mass.begin(row); m != system.mass.end(row); ++m, ++k, ++e)
      {
        const std::size_t at = run.values + static_cast<std::size_t>(e) * run.rows + r;
        mass[at] = m->value();
        damping[at] = d[e];
        stiffness[at] = k->value();
      }
    }
    runs.push_back(run);
  }
  find_stretches();
  cut_runs_at_stretches();
}

void PatternOperators::add_shift(const dealii::Vector<double>& r,
                                 dealii::Vector<double>& x) const
{
  for (const Shift& b : block_shifts)
    if (b.gamma != 0.)
      for (unsigned int i = b.first; i < b.last; ++i)
        x[i] += b.gamma * r[i];
}

void PatternOperators::solve_history(const dealii::Vector<double>& h,
                                     const dealii::Vector<double>& r,
                                     const SparseDirectSolver& inverse,
                                     dealii::Vector<double>& out) const
{
  out.reinit(system.n_dofs(), true);
  history(h, r, out);
  inverse.solve(out);
  add_shift(r, out);
}

unsigned int PatternOperators::rows_with_damping_entries() const
{
  return damped_rows;
}

PatternOperators::RowEntries PatternOperators::row_entries(const unsigned int i) const
{
  RowEntries r;
  r.damping = damping_row(i);
  for (auto m = system.mass.begin(i); m != system.mass.end(i); ++m)
  {
    r.offsets.push_back(static_cast<int>(m->column()) - static_cast<int>(i));
    r.mass.push_back(m->value());
  }
  return r;
}

namespace
{
/// True if @p a comes before @p b in a deal.II row: the diagonal first, then by column.
bool before(const int a, const int b)
{
  return a == 0 ? b != 0 : (b != 0 && a < b);
}

/// The offsets of @p a and @p b merged in the pattern's order (empty if they
/// disagree on it, which deal.II's rows do not).
std::vector<int> merged_offsets(const std::vector<int>& a, const std::vector<int>& b)
{
  std::vector<int> u;
  std::size_t i = 0, j = 0;
  while (i < a.size() || j < b.size())
    if (j == b.size() || (i < a.size() && before(a[i], b[j])))
      u.push_back(a[i++]);
    else if (i == a.size() || before(b[j], a[i]))
      u.push_back(b[j++]);
    else
      u.push_back(a[i++]), ++j;
  for (std::size_t k = 1; k < u.size(); ++k)
    if (!before(u[k - 1], u[k]))
      return {};
  return u;
}
} // namespace

void PatternOperators::find_stretches()
{
  // The rows repeating with period 2 (find_repeating_rows()), compared by
  // their entries. Rows s and s + 1 open a stretch if their offsets merge
  // (at most 8); every row of a stretch must reach the merged offsets inside
  // the vectors.
  constexpr std::size_t max_offsets = 8;
  const int n = system.n_dofs();
  std::vector<RowEntries> entries(n);
  for (int i = 0; i < n; ++i)
  {
    entries[i] = row_entries(i);
    damped_rows += std::any_of(entries[i].damping.begin(), entries[i].damping.end(),
                               [](const double d) { return d != 0.; });
  }
  const auto merged = [&](const int s)
  { return merged_offsets(entries[s].offsets, entries[s + 1].offsets); };
  int lowest = 0, highest = 0; // the offsets of the stretch opened last
  const auto fits = [&](const int i) { return i + lowest >= 0 && i + highest < n; };
  const auto opens = [&](const int s)
  {
    const std::vector<int> u = merged(s);
    if (u.empty() || u.size() > max_offsets)
      return false;
    lowest = *std::min_element(u.begin(), u.end());
    highest = *std::max_element(u.begin(), u.end());
    return fits(s) && fits(s + 1);
  };
  for (const RepeatingRows& found : find_repeating_rows(
           0, n, minimum_stretch, opens, fits,
           [&](const int i, const int j) { return entries[i] == entries[j]; }))
  {
    const int start = found.first;
    const std::vector<int> u = merged(start);
    Stretch st;
    st.first = start;
    st.last = found.last;
    st.n_exceptions = found.exceptions.size();
    st.offsets = u;
    st.mass.assign(2 * u.size(), 0.);
    st.damping.assign(2 * u.size(), 0.);
    for (unsigned int p = 0; p < 2; ++p)
    {
      const RowEntries& row = entries[start + p];
      for (std::size_t e = 0; e < row.offsets.size(); ++e)
      {
        const std::size_t k = std::find(u.begin(), u.end(), row.offsets[e]) - u.begin();
        st.mass[2 * k + p] = row.mass[e];
        st.damping[2 * k + p] = row.damping[e];
      }
    }
    std::vector<unsigned int> grouped;
    std::vector<const RowEntries*> grouped_entries;
    for (const int i : found.exceptions)
      if (merged_offsets(u, entries[i].offsets) == u)
      {
        grouped.push_back(i);
        grouped_entries.push_back(&entries[i]);
      }
      else
      {
        exceptions.push_back(i);
        exception_entries.push_back(entries[i]);
      }
    st.group(grouped, grouped_entries);
    st.undamped = std::all_of(st.damping.begin(), st.damping.end(),
                              [](const double d) { return d == 0.; });
    stretches.push_back(std::move(st));
  }
}

void PatternOperators::Stretch::group(const std::vector<unsigned int>& rows,
                                      const std::vector<const RowEntries*>& entries)
{
  const std::size_t groups = (rows.size() + 3) / 4, E = offsets.size();
  grouped_rows.assign(4 * groups, 0);
  grouped_mass.assign(4 * groups * E, 0.);
  grouped_damping.assign(4 * groups * E, 0.);
  for (std::size_t g = 0; g < groups; ++g)
    for (std::size_t lane = 0; lane < 4; ++lane)
    {
      const std::size_t x = std::min(4 * g + lane, rows.size() - 1);
      grouped_rows[4 * g + lane] = rows[x];
      const RowEntries& row = *entries[x];
      for (std::size_t e = 0; e < row.offsets.size(); ++e)
      {
        const std::size_t k =
            std::find(offsets.begin(), offsets.end(), row.offsets[e]) - offsets.begin();
        grouped_mass[(g * E + k) * 4 + lane] = row.mass[e];
        grouped_damping[(g * E + k) * 4 + lane] = row.damping[e];
      }
    }
}

void PatternOperators::cut_runs_at_stretches()
{
  const unsigned int n = system.n_dofs();
  std::vector<char> in_stretch(n, 0);
  for (const Stretch& st : stretches)
    std::fill(in_stretch.begin() + st.first, in_stretch.begin() + st.last, 1);
  for (const Run& run : runs)
    for (unsigned int r = 0; r < run.rows;)
    {
      if (in_stretch[run.first + r * run.stride])
      {
        ++r;
        continue;
      }
      unsigned int e = r;
      while (e < run.rows && !in_stretch[run.first + e * run.stride])
        ++e;
      Run piece = run;
      piece.first = run.first + r * run.stride;
      piece.rows = e - r;
      piece.values = run.values + r;
      history_runs.push_back(piece);
      r = e;
    }
}

unsigned int PatternOperators::rows_in_stretches() const
{
  unsigned int rows = 0;
  for (const Stretch& st : stretches)
    rows += st.last - st.first - st.n_exceptions;
  return rows;
}

void PatternOperators::set_time(const double t) const
{
  if (system.has_time_dependent_load())
    system.load_at(t, load);
}

namespace
{
/// Rows at once in the passes: their partial sums stay in the first-level cache.
constexpr unsigned int rows_per_pass = 256;

/**
 * s[r] += m[r] h[r S] + d[r] x[r S] over @p rows rows of stride S: one entry
 * of each row (the arrays start at the block's first row), rows independent.
 */
template <unsigned int S>
__attribute__((target_clones("avx2", "default"))) void
add_entry(const unsigned int rows, const double* __restrict m, const double* __restrict d,
          const double* __restrict h, const double* __restrict x, double* __restrict s)
{
  for (unsigned int r = 0; r < rows; ++r)
    s[r] += m[r] * h[S * r] + d[r] * x[S * r];
}

/// fq[r] += m[r] (qp[r S] - v[r S]), fv[r] += m[r] vp[r S] + d[r] v[r S] + k[r] q[r S].
template <unsigned int S>
__attribute__((target_clones("avx2", "default"))) void
add_motion_entry(const unsigned int rows, const double* __restrict m,
                 const double* __restrict d, const double* __restrict k,
                 const double* __restrict q, const double* __restrict v,
                 const double* __restrict qp, const double* __restrict vp,
                 double* __restrict fq, double* __restrict fv)
{
  for (unsigned int r = 0; r < rows; ++r)
  {
    fq[r] += m[r] * (qp[S * r] - v[S * r]);
    fv[r] += m[r] * vp[S * r] + d[r] * v[S * r] + k[r] * q[S * r];
  }
}

template <typename F>
void with_stride(const unsigned int stride, const F& f)
{
  if (stride == 1)
    f(std::integral_constant<unsigned int, 1>{});
  else if (stride == 2)
    f(std::integral_constant<unsigned int, 2>{});
  else
    f(std::integral_constant<unsigned int, 3>{});
}

/**
 * out = f + M h + D r on the rows [@p first, @p last) of a stretch from its
 * two rows' coefficients (@p m, @p d: [offset index * 2 + parity], parity 0
 * at @p first), four rows at once (two of each parity), each row's terms
 * summed in a register in the offsets' order, each term as the runs' passes
 * form it: s += m h + d r. Compiled for AVX2 beside the baseline (no fused
 * multiply-add: the same bits either way).
 */
template <unsigned int E>
__attribute__((target_clones("avx2", "default"))) void stretch_history(
    const unsigned int first, const unsigned int last, const int* __restrict offsets,
    const double* __restrict m, const double* __restrict d, const double* __restrict f,
    const double* __restrict h, const double* __restrict r, double* __restrict out)
{
  using Quad = double __attribute__((vector_size(32)));
  const auto load = [](const double* x)
  {
    Quad v;
    std::memcpy(&v, x, sizeof v);
    return v;
  };
  Quad mq[E], dq[E];
  for (unsigned int e = 0; e < E; ++e)
  {
    mq[e] = Quad{m[2 * e], m[2 * e + 1], m[2 * e], m[2 * e + 1]};
    dq[e] = Quad{d[2 * e], d[2 * e + 1], d[2 * e], d[2 * e + 1]};
  }
  unsigned int i = first;
  for (; i + 4 <= last; i += 4)
  {
    Quad s = load(f + i);
    for (unsigned int e = 0; e < E; ++e)
      s += mq[e] * load(h + i + offsets[e]) + dq[e] * load(r + i + offsets[e]);
    std::memcpy(out + i, &s, sizeof s);
  }
  for (; i < last; ++i)
  {
    const unsigned int p = (i - first) % 2;
    double s = f[i];
    for (unsigned int e = 0; e < E; ++e)
      s += m[2 * e + p] * h[i + offsets[e]] + d[2 * e + p] * r[i + offsets[e]];
    out[i] = s;
  }
}

/**
 * out = f + M h on the rows [@p first, @p last) of a stretch whose damping
 * coefficients are all zero (the damping split, or D = 0): stretch_history()
 * without the damping's terms.
 */
template <unsigned int E>
__attribute__((target_clones("avx2", "default"))) void
stretch_mass_history(const unsigned int first, const unsigned int last,
                     const int* __restrict offsets, const double* __restrict m,
                     const double* __restrict f, const double* __restrict h,
                     double* __restrict out)
{
  using Quad = double __attribute__((vector_size(32)));
  const auto load = [](const double* x)
  {
    Quad v;
    std::memcpy(&v, x, sizeof v);
    return v;
  };
  Quad mq[E];
  for (unsigned int e = 0; e < E; ++e)
    mq[e] = Quad{m[2 * e], m[2 * e + 1], m[2 * e], m[2 * e + 1]};
  unsigned int i = first;
  for (; i + 4 <= last; i += 4)
  {
    Quad s = load(f + i);
    for (unsigned int e = 0; e < E; ++e)
      s += mq[e] * load(h + i + offsets[e]);
    std::memcpy(out + i, &s, sizeof s);
  }
  for (; i < last; ++i)
  {
    const unsigned int p = (i - first) % 2;
    double s = f[i];
    for (unsigned int e = 0; e < E; ++e)
      s += m[2 * e + p] * h[i + offsets[e]];
    out[i] = s;
  }
}

/// f(std::integral_constant<unsigned int, E>) for E = @p n_offsets (1 to 8):
/// the kernels' loops over the offsets unrolled.
template <typename F>
void with_offsets(const unsigned int n_offsets, const F& f)
{
  switch (n_offsets)
  {
  case 1:
    return f(std::integral_constant<unsigned int, 1>{});
  case 2:
    return f(std::integral_constant<unsigned int, 2>{});
  case 3:
    return f(std::integral_constant<unsigned int, 3>{});
  case 4:
    return f(std::integral_constant<unsigned int, 4>{});
  case 5:
    return f(std::integral_constant<unsigned int, 5>{});
  case 6:
    return f(std::integral_constant<unsigned int, 6>{});
  case 7:
    return f(std::integral_constant<unsigned int, 7>{});
  default:
    return f(std::integral_constant<unsigned int, 8>{});
  }
}

/**
 * The exceptions of a stretch four at a time, one row per lane (@p rows:
 * four per group), from their M and D values [group][offset index][lane]:
 * each lane sums its row's terms as stretch_history() does, in the same
 * order, the stretch's offsets a row lacks entering with 0.
 */
template <unsigned int E>
__attribute__((target_clones("avx2", "default"))) void exception_history(
    const std::size_t groups, const unsigned int* rows, const int* __restrict offsets,
    const double* __restrict m, const double* __restrict d, const double* __restrict f,
    const double* __restrict h, const double* __restrict r, double* __restrict out)
{
  using Quad = double __attribute__((vector_size(32)));
  for (std::size_t g = 0; g < groups; ++g, rows += 4, m += 4 * E, d += 4 * E)
  {
    const unsigned int r0 = rows[0], r1 = rows[1], r2 = rows[2], r3 = rows[3];
    Quad s = {f[r0], f[r1], f[r2], f[r3]};
    for (unsigned int e = 0; e < E; ++e)
    {
      const int o = offsets[e];
      Quad me, de;
      std::memcpy(&me, m + 4 * e, sizeof me);
      std::memcpy(&de, d + 4 * e, sizeof de);
      s += me * Quad{h[r0 + o], h[r1 + o], h[r2 + o], h[r3 + o]} +
           de * Quad{r[r0 + o], r[r1 + o], r[r2 + o], r[r3 + o]};
    }
    // In reverse: a padded group's repeated last row gets its value last.
    out[r3] = s[3];
    out[r2] = s[2];
    out[r1] = s[1];
    out[r0] = s[0];
  }
}

} // namespace

void PatternOperators::history(const dealii::Vector<double>& h,
                               const dealii::Vector<double>& r,
                               dealii::Vector<double>& out) const
{
  double s[rows_per_pass];
  for (const Run& run : history_runs)
    for (unsigned int first = 0; first < run.rows; first += rows_per_pass)
    {
      const unsigned int rows = std::min(rows_per_pass, run.rows - first),
                         i0 = run.first + first * run.stride;
      for (unsigned int j = 0; j < rows; ++j)
        s[j] = load[i0 + j * run.stride];
      for (unsigned int e = 0; e < run.n_offsets; ++e)
      {
        const std::size_t at =
            run.values + static_cast<std::size_t>(e) * run.leading + first;
        const int o = offsets[run.first_offset + e];
        const double *m = mass.data() + at, *d = damping.data() + at,
                     *hh = h.begin() + i0 + o, *rr = r.begin() + i0 + o;
        if (rows < 4) // a few rows: no call through the clones' resolver
          for (unsigned int j = 0; j < rows; ++j)
            s[j] += m[j] * hh[run.stride * j] + d[j] * rr[run.stride * j];
        else
          with_stride(run.stride, [&](auto S)
                      { add_entry<decltype(S)::value>(rows, m, d, hh, rr, s); });
      }
      for (unsigned int j = 0; j < rows; ++j)
        out[i0 + j * run.stride] = s[j];
    }
  for (const Stretch& st : stretches)
  {
    const std::size_t groups = st.grouped_rows.size() / 4;
    with_offsets(
        st.offsets.size(),
        [&](auto E)
        {
          constexpr unsigned int e = decltype(E)::value;
          if (st.undamped)
            stretch_mass_history<e>(st.first, st.last, st.offsets.data(), st.mass.data(),
                                    load.begin(), h.begin(), out.begin());
          else
            stretch_history<e>(st.first, st.last, st.offsets.data(), st.mass.data(),
                               st.damping.data(), load.begin(), h.begin(), r.begin(),
                               out.begin());
          if (groups > 0)
            exception_history<e>(groups, st.grouped_rows.data(), st.offsets.data(),
                                 st.grouped_mass.data(), st.grouped_damping.data(),
                                 load.begin(), h.begin(), r.begin(), out.begin());
        });
  }
  for (std::size_t x = 0; x < exceptions.size(); ++x)
  {
    const unsigned int i = exceptions[x];
    const RowEntries& row = exception_entries[x];
    double sum = load[i];
    for (std::size_t e = 0; e < row.offsets.size(); ++e)
      sum += row.mass[e] * h[i + row.offsets[e]] + row.damping[e] * r[i + row.offsets[e]];
    out[i] = sum;
  }
}

void PatternOperators::motion(const double* q, const double* v, const double* qp,
                              const double* vp, double* r_q, double* r_v) const
{
  if (split)
    throw std::logic_error("PatternOperators::motion() with the damping split");
  double fq[rows_per_pass], fv[rows_per_pass];
  for (const Run& run : runs)
    for (unsigned int first = 0; first < run.rows; first += rows_per_pass)
    {
      const unsigned int rows = std::min(rows_per_pass, run.rows - first),
                         i0 = run.first + first * run.stride;
      for (unsigned int j = 0; j < rows; ++j)
      {
        fq[j] = 0.;
        fv[j] = -load[i0 + j * run.stride];
      }
      for (unsigned int e = 0; e < run.n_offsets; ++e)
      {
        const std::size_t at =
            run.values + static_cast<std::size_t>(e) * run.leading + first;
        const int o = offsets[run.first_offset + e];
        with_stride(run.stride,
                    [&](auto S)
                    {
                      add_motion_entry<decltype(S)::value>(
                          rows, mass.data() + at, damping.data() + at,
                          stiffness.data() + at, q + i0 + o, v + i0 + o, qp + i0 + o,
                          vp + i0 + o, fq, fv);
                    });
      }
      for (unsigned int j = 0; j < rows; ++j)
      {
        r_q[i0 + j * run.stride] = fq[j];
        r_v[i0 + j * run.stride] = fv[j];
      }
    }
}
} // namespace pantocat
