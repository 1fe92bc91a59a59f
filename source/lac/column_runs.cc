#include <pantocat/lac/column_runs.h>

#include <algorithm>

namespace pantocat
{
namespace
{
/// ColumnRuns::add() (a separate function for its AVX2 clone).
__attribute__((target_clones("avx2", "default"))) void
add_runs(const unsigned int m, const double* __restrict c, const double* __restrict d,
         const unsigned int* __restrict run_start, const ColumnRuns::Run* __restrict runs,
         const double* __restrict value, double* __restrict y, double* __restrict z)
{
  for (unsigned int l = 0; l < m; ++l)
  {
    const double cl = c[l], dl = d ? d[l] : 0.;
    if (cl == 0. && dl == 0.)
      continue;
    for (unsigned int r = run_start[l]; r < run_start[l + 1]; ++r)
    {
      const double* __restrict v = value + runs[r].offset;
      double* __restrict a = y + runs[r].first;
      if (d)
      {
        double* __restrict b = z + runs[r].first;
        for (unsigned int j = 0; j < runs[r].length; ++j)
        {
          a[j] += cl * v[j];
          b[j] += dl * v[j];
        }
      }
      else
        for (unsigned int j = 0; j < runs[r].length; ++j)
          a[j] += cl * v[j];
    }
  }
}
} // namespace

void ColumnRuns::initialize(const std::vector<SparseRow>& columns,
                            const unsigned int n_dofs)
{
  clear();
  std::vector<char> is_reached(n_dofs, 0);
  for (const SparseRow& c : columns)
  {
    for (std::size_t k = 0; k < c.size(); ++k)
    {
      if (k > 0 && c.index[k] == c.index[k - 1] + 1)
        ++runs.back().length;
      else
        runs.push_back({c.index[k], 1, value.size()});
      value.push_back(c.value[k]);
      is_reached[c.index[k]] = 1;
    }
    run_start.push_back(runs.size());
  }
  for (unsigned int i = 0; i < n_dofs; ++i)
    if (is_reached[i])
    {
      if (!ranges.empty() && ranges.back().last == static_cast<int>(i))
        ++ranges.back().last;
      else
        ranges.push_back({static_cast<int>(i), static_cast<int>(i) + 1});
    }
}

void ColumnRuns::clear()
{
  runs.clear();
  run_start.assign(1, 0);
  value.clear();
  ranges.clear();
}

const RowRanges* ColumnRuns::reach_of(const double* c, const double* d,
                                      RowRanges& out) const
{
  const unsigned int m = run_start.size() - 1;
  const auto counts = [&](const unsigned int l)
  { return c[l] != 0. || (d && d[l] != 0.); };
  unsigned int counted = 0;
  for (unsigned int l = 0; l < m; ++l)
    counted += counts(l);
  if (counted == m)
    return &ranges;
  gathered.clear();
  for (unsigned int l = 0; l < m; ++l)
    if (counts(l))
      for (unsigned int r = run_start[l]; r < run_start[l + 1]; ++r)
        gathered.push_back({static_cast<int>(runs[r].first),
                            static_cast<int>(runs[r].first + runs[r].length)});
  std::sort(gathered.begin(), gathered.end(),
            [](const RowRange& a, const RowRange& b) { return a.first < b.first; });
  out.clear();
  for (const RowRange& r : gathered)
    if (!out.empty() && r.first <= out.back().last)
      out.back().last = std::max(out.back().last, r.last);
    else
      out.push_back(r);
  return &out;
}

void ColumnRuns::add(const double* c, const double* d, double* y, double* z) const
{
  add_runs(run_start.size() - 1, c, d, run_start.data(), runs.data(), value.data(), y, z);
}
} // namespace pantocat
