#include <pantocat/lac/local_columns.h>

#include <algorithm>

namespace pantocat
{
void merge_ranges(const RowRanges& a, const RowRanges& b, RowRanges& out)
{
  out.clear();
  std::size_t i = 0, j = 0;
  while (i < a.size() || j < b.size())
  {
    const RowRange& r =
        j == b.size() || (i < a.size() && a[i].first <= b[j].first) ? a[i++] : b[j++];
    if (!out.empty() && r.first <= out.back().last)
      out.back().last = std::max(out.back().last, r.last);
    else
      out.push_back(r);
  }
}

RowRanges union_of(const RowRanges& a, const RowRanges& b)
{
  RowRanges merged;
  merge_ranges(a, b, merged);
  return merged;
}

void add_ranges(RowRanges& into, const RowRanges& b, RowRanges& scratch)
{
  merge_ranges(into, b, scratch);
  into.swap(scratch);
}

void LocalColumns::reinit(const unsigned int n)
{
  InterleavedColumns::reinit(n);
  rows.clear();
}

void LocalColumns::clear()
{
  double* x = InterleavedColumns::data();
  for (const RowRange& r : rows)
    std::fill(x + static_cast<std::size_t>(r.first) * width,
              x + static_cast<std::size_t>(r.last) * width, 0.);
  rows.clear();
}

void LocalColumns::take_in(const std::vector<unsigned int>& sorted)
{
  added.clear();
  for (const unsigned int i : sorted)
    if (!added.empty() && static_cast<int>(i) <= added.back().last)
      added.back().last = std::max<int>(added.back().last, i + 1);
    else
      added.push_back({static_cast<int>(i), static_cast<int>(i) + 1});
  add_ranges(rows, added, merged);
}

void LocalColumns::add_row(const unsigned int k, const SparseRow& row,
                           const double factor)
{
  InterleavedColumns::add_row(k, row, factor);
  scratch = row.index;
  std::sort(scratch.begin(), scratch.end());
  take_in(scratch);
}

void LocalColumns::set(const unsigned int i, const unsigned int k, const double value)
{
  InterleavedColumns::operator()(i, k) = value;
  const auto in = [i](const RowRange& r)
  { return r.first <= static_cast<int>(i) && static_cast<int>(i) < r.last; };
  if (std::none_of(rows.begin(), rows.end(), in)) // else the reach holds row i
  {
    scratch.assign(1, i);
    take_in(scratch);
  }
}

void LocalColumns::solve(const SparseDirectSolver& A)
{
  A.solve_local(InterleavedColumns::data(), width, rows);
}

void LocalColumns::scale_rows(const dealii::Vector<double>& scaling)
{
  double* __restrict x = InterleavedColumns::data();
  const double* __restrict d = scaling.begin();
  for (const RowRange& r : rows)
    for (int i = r.first; i < r.last; ++i)
      for (unsigned int k = 0; k < width; ++k)
        x[i * width + k] *= d[i];
}

void LocalColumns::add_combination(const std::array<double, width>& c,
                                   dealii::Vector<double>& out) const
{
  const double* __restrict x = data();
  double* __restrict y = out.begin();
  for (const RowRange& r : rows)
    for (int i = r.first; i < r.last; ++i)
      y[i] += c[0] * x[width * i] + c[1] * x[width * i + 1] + c[2] * x[width * i + 2] +
              c[3] * x[width * i + 3];
}
} // namespace pantocat
