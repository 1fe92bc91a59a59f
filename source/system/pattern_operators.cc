#include <pantocat/system/pattern_operators.h>

#include <algorithm>
#include <type_traits>

namespace pantocat
{
PatternOperators::PatternOperators(const SemiDiscreteSystem& system)
    : system(system), load(system.load)
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
      auto d = system.damping.begin(row);
      auto k = system.stiffness.begin(row);
      unsigned int e = 0;
      for (auto m = system.mass.begin(row); m != system.mass.end(row); ++m, ++d, ++k, ++e)
      {
        const std::size_t at = run.values + static_cast<std::size_t>(e) * run.rows + r;
        mass[at] = m->value();
        damping[at] = d->value();
        stiffness[at] = k->value();
      }
    }
    runs.push_back(run);
  }
}

void PatternOperators::set_time(const double t) const
{
  if (system.has_time_dependent_load())
    system.load_at(t, load);
}

namespace
{
/// Rows at once in the passes: their partial sums stay in the first-level cache.
constexpr unsigned int block = 256;

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
} // namespace

void PatternOperators::history(const dealii::Vector<double>& h,
                               const dealii::Vector<double>& r,
                               dealii::Vector<double>& out) const
{
  double s[block];
  for (const Run& run : runs)
    for (unsigned int first = 0; first < run.rows; first += block)
    {
      const unsigned int rows = std::min(block, run.rows - first),
                         i0 = run.first + first * run.stride;
      for (unsigned int j = 0; j < rows; ++j)
        s[j] = load[i0 + j * run.stride];
      for (unsigned int e = 0; e < run.n_offsets; ++e)
      {
        const std::size_t at =
            run.values + static_cast<std::size_t>(e) * run.rows + first;
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
}

void PatternOperators::motion(const double* q, const double* v, const double* qp,
                              const double* vp, double* r_q, double* r_v) const
{
  double fq[block], fv[block];
  for (const Run& run : runs)
    for (unsigned int first = 0; first < run.rows; first += block)
    {
      const unsigned int rows = std::min(block, run.rows - first),
                         i0 = run.first + first * run.stride;
      for (unsigned int j = 0; j < rows; ++j)
      {
        fq[j] = 0.;
        fv[j] = -load[i0 + j * run.stride];
      }
      for (unsigned int e = 0; e < run.n_offsets; ++e)
      {
        const std::size_t at =
            run.values + static_cast<std::size_t>(e) * run.rows + first;
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
