#include <pantocat/constrained_fast/truncated_columns.h>

#include <deal.II/base/exceptions.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <iterator>

namespace pantocat
{
SparseRow truncated(const dealii::Vector<double>& column)
{
  const double tolerance = 1e-16 * column.linfty_norm();
  SparseRow row;
  for (unsigned int i = 0; i < column.size(); ++i)
    if (std::abs(column[i]) > tolerance)
      row.add(i, column[i]);
  return row;
}

namespace
{
/// A reached unknown's entries, by column: (l, value of X, value of X').
struct UnknownEntries
{
  unsigned int i;
  unsigned char reached_by = 0;
  std::vector<unsigned int> l;
  std::vector<std::array<double, 2>> v;
};

/// The reached unknowns in order, each with its entries in the order of columns.
std::vector<UnknownEntries> entries_by_unknown(const std::vector<SparseRow>& columns,
                                               const std::vector<SparseRow>& partners)
{
  struct Entry
  {
    unsigned int i, l, set;
    double value;
  };
  std::vector<Entry> entries;
  for (unsigned int set = 0; set < (partners.empty() ? 1u : 2u); ++set)
    for (unsigned int l = 0; l < columns.size(); ++l)
    {
      const SparseRow& c = set == 0 ? columns[l] : partners[l];
      for (std::size_t k = 0; k < c.size(); ++k)
        entries.push_back({c.index[k], l, set, c.value[k]});
    }
  std::stable_sort(entries.begin(), entries.end(),
                   [](const Entry& a, const Entry& b)
                   { return a.i != b.i ? a.i < b.i : a.l < b.l; });
  std::vector<UnknownEntries> by_unknown;
  for (std::size_t e = 0; e < entries.size(); ++e)
  {
    const Entry& x = entries[e];
    if (by_unknown.empty() || by_unknown.back().i != x.i)
      by_unknown.push_back({x.i, 0, {}, {}});
    UnknownEntries& u = by_unknown.back();
    u.reached_by |= static_cast<unsigned char>(1u << x.set);
    if (e == 0 || entries[e - 1].i != x.i || entries[e - 1].l != x.l)
    {
      u.l.push_back(x.l);
      u.v.push_back({{0., 0.}});
    }
    u.v.back()[x.set] = x.value;
  }
  return by_unknown;
}

using Quad = double __attribute__((vector_size(32)));

/// What the slices' sums s (of c) and t (of d) add to: y += s (set 0 reaches),
/// y += s and z += t (set 0), or y += s (set 0), then y += t (set 1).
enum class Target : int
{
  y,
  y_and_z,
  y_then_partners
};

/**
 * The sums of every slice, four unknowns at once, and their additions
 * (Target). The sum of lane j: its products in the order of the columns,
 * zeros included (a zero product leaves a sum that starts at +0 as it is:
 * it is never -0), so each unknown's sum is that over its entries alone.
 */
__attribute__((target_clones("avx2", "default"))) void
add_slices(const TruncatedColumns::Slice* slices, const std::size_t count,
           const unsigned int* __restrict column, const double* __restrict value,
           const unsigned int sets, const unsigned int set_d, const double* __restrict c,
           const double* __restrict d, const Target target, double* __restrict y,
           double* __restrict z)
{
  for (std::size_t k = 0; k < count; ++k)
  {
    const TruncatedColumns::Slice& slice = slices[k];
    const double* v = value + slice.offset;
    const unsigned int* l = column + slice.first;
    Quad s = {0., 0., 0., 0.}, t = {0., 0., 0., 0.};
    if (d)
      for (unsigned int e = 0; e < slice.length; ++e)
      {
        Quad a, b;
        std::memcpy(&a, v + 4 * sets * e, sizeof a);
        std::memcpy(&b, v + 4 * (sets * e + set_d), sizeof b);
        s += a * c[l[e]];
        t += b * d[l[e]];
      }
    else
      for (unsigned int e = 0; e < slice.length; ++e)
      {
        Quad a;
        std::memcpy(&a, v + 4 * sets * e, sizeof a);
        s += a * c[l[e]];
      }
    for (unsigned int j = 0; j < 4; ++j)
    {
      const int i = slice.unknown[j];
      const unsigned char reached = slice.reached_by[j];
      if (i < 0)
        break;
      if (target == Target::y_then_partners)
      {
        if (reached & 1u)
          y[i] += s[j];
        if (reached & 2u)
          y[i] += t[j];
      }
      else if (reached & 1u)
      {
        y[i] += s[j];
        if (target == Target::y_and_z)
          z[i] += t[j];
      }
    }
  }
}

/// y += acc (and z += acc_z) on @p ranges, and acc (acc_z) = 0 there.
__attribute__((target_clones("avx2", "default"))) void
add_and_clear(const RowRange* ranges, const std::size_t count, double* __restrict acc,
              double* __restrict y, double* __restrict acc_z, double* __restrict z)
{
  for (std::size_t r = 0; r < count; ++r)
    for (int i = ranges[r].first; i < ranges[r].last; ++i)
    {
      y[i] += acc[i];
      acc[i] = 0.;
      if (z)
      {
        z[i] += acc_z[i];
        acc_z[i] = 0.;
      }
    }
}
} // namespace

void TruncatedColumns::initialize(const std::vector<SparseRow>& columns,
                                  const unsigned int n_dofs,
                                  const std::vector<SparseRow>& partners)
{
  AssertThrow(partners.empty() || partners.size() == columns.size(),
              dealii::ExcDimensionMismatch(partners.size(), columns.size()));
  m = columns.size();
  sets = partners.empty() ? 1 : 2;
  const std::vector<UnknownEntries> unknowns = entries_by_unknown(columns, partners);
  pattern_entries = 0;
  for (const UnknownEntries& u : unknowns)
    pattern_entries += u.l.size();
  // Slices: consecutive reached unknowns, four at most, while the slice's
  // columns are no more than about twice their entries (an unknown of the
  // other wire, reached by other columns, starts a new slice).
  slices.clear();
  column.clear();
  value.clear();
  slot.assign(n_dofs, -1);
  std::vector<unsigned int> together, with;
  std::size_t u = 0;
  while (u < unknowns.size())
  {
    std::size_t end = u + 1;
    together = unknowns[u].l;
    std::size_t entries = unknowns[u].l.size();
    while (end < unknowns.size() && end - u < 4)
    {
      const std::vector<unsigned int>& l = unknowns[end].l;
      with.clear();
      std::set_union(together.begin(), together.end(), l.begin(), l.end(),
                     std::back_inserter(with));
      if (with.size() * (end - u + 1) > 2 * (entries + l.size()) + 12)
        break;
      together.swap(with);
      entries += l.size();
      ++end;
    }
    Slice slice;
    slice.first = column.size();
    slice.length = together.size();
    slice.offset = value.size();
    column.insert(column.end(), together.begin(), together.end());
    value.resize(value.size() + 4 * sets * slice.length, 0.);
    for (std::size_t j = 0; j < end - u; ++j)
    {
      const UnknownEntries& x = unknowns[u + j];
      slice.unknown[j] = static_cast<int>(x.i);
      slice.reached_by[j] = x.reached_by;
      slot[x.i] = static_cast<int>(4 * slices.size() + j);
      for (std::size_t k = 0, e = 0; k < x.l.size(); ++k)
      {
        while (together[e] != x.l[k])
          ++e;
        for (unsigned int set = 0; set < sets; ++set)
          value[slice.offset + 4 * (sets * e + set) + j] = x.v[k][set];
      }
    }
    slices.push_back(slice);
    u = end;
  }
  // add() and add_with_partners() read the columns by runs.
  column_runs[0].initialize(columns, n_dofs);
  column_runs[1].clear();
  if (sets == 2)
    column_runs[1].initialize(partners, n_dofs);
  acc.assign(n_dofs, 0.);
  acc_d.assign(n_dofs, 0.);
  // Runs of a few entries (an FDM's M^-1 G^T: a dropper's two nodes) cost
  // more per entry than the slices.
  const std::size_t run_count = column_runs[0].n_runs() + column_runs[1].n_runs();
  const std::size_t run_entries = column_runs[0].n_entries() + column_runs[1].n_entries();
  by_runs = run_entries >= 4 * run_count;
}

std::size_t TruncatedColumns::n_slice_operations() const
{
  return sets * column.size();
}

void TruncatedColumns::row_products(const SparseRow& g, std::vector<double>& out) const
{
  row_products(g, 0, out);
}

void TruncatedColumns::partner_row_products(const SparseRow& g,
                                            std::vector<double>& out) const
{
  Assert(sets == 2, dealii::ExcMessage("no partner columns stored"));
  row_products(g, 1, out);
}

void TruncatedColumns::row_products(const SparseRow& g, const unsigned int set,
                                    std::vector<double>& out) const
{
  // The slice's zeros add +-0 to sums that are never -0: no change.
  out.assign(m, 0.);
  for (std::size_t k = 0; k < g.size(); ++k)
  {
    const unsigned int i = g.index[k];
    if (i >= slot.size() || slot[i] < 0)
      continue;
    const Slice& slice = slices[slot[i] / 4];
    const double* v = value.data() + slice.offset + 4 * set + slot[i] % 4;
    const unsigned int* l = column.data() + slice.first;
    for (unsigned int e = 0; e < slice.length; ++e)
      out[l[e]] += g.value[k] * v[4 * sets * e];
  }
}

void TruncatedColumns::add(const std::vector<double>& c, dealii::Vector<double>& y) const
{
  if (!by_runs)
  {
    add_slices(slices.data(), slices.size(), column.data(), value.data(), sets, 0,
               c.data(), nullptr, Target::y, y.begin(), nullptr);
    return;
  }
  // An unknown no column reaches is not touched (y_i += 0 would make a -0 +0).
  const ColumnRuns& x = column_runs[0];
  x.add(c.data(), nullptr, acc.data(), nullptr);
  add_and_clear(x.reached().data(), x.reached().size(), acc.data(), y.begin(), nullptr,
                nullptr);
}

TruncatedColumns::Sums TruncatedColumns::sum(const std::vector<double>& c) const
{
  Assert(by_runs, dealii::ExcMessage("sum() needs the columns by runs"));
  const ColumnRuns& x = column_runs[0];
  x.add(c.data(), nullptr, acc.data(), nullptr);
  return {acc.data(), nullptr, x.reach_of(c.data(), nullptr, reach_w[0]), nullptr};
}

TruncatedColumns::Sums TruncatedColumns::sum(const std::vector<double>& c,
                                             const std::vector<double>& d) const
{
  Assert(by_runs, dealii::ExcMessage("sum() needs the columns by runs"));
  const ColumnRuns& x = column_runs[0];
  x.add(c.data(), d.data(), acc.data(), acc_d.data());
  const RowRanges* rows = x.reach_of(c.data(), d.data(), reach_w[0]);
  return {acc.data(), acc_d.data(), rows, rows};
}

TruncatedColumns::Sums
TruncatedColumns::sum_with_partners(const std::vector<double>& c,
                                    const std::vector<double>& d) const
{
  Assert(sets == 2, dealii::ExcMessage("no partner columns stored"));
  Assert(by_runs, dealii::ExcMessage("sum_with_partners() needs the columns by runs"));
  column_runs[0].add(c.data(), nullptr, acc.data(), nullptr);
  column_runs[1].add(d.data(), nullptr, acc_d.data(), nullptr);
  return {acc.data(), acc_d.data(),
          column_runs[0].reach_of(c.data(), nullptr, reach_w[0]),
          column_runs[1].reach_of(d.data(), nullptr, reach_w[1])};
}

void TruncatedColumns::add(const std::vector<double>& c, dealii::Vector<double>& y,
                           const std::vector<double>& d, dealii::Vector<double>& z) const
{
  if (!by_runs)
  {
    add_slices(slices.data(), slices.size(), column.data(), value.data(), sets, 0,
               c.data(), d.data(), Target::y_and_z, y.begin(), z.begin());
    return;
  }
  const Sums s = sum(c, d);
  add_and_clear(s.first_rows->data(), s.first_rows->size(), s.first, y.begin(), s.second,
                z.begin());
}

void TruncatedColumns::add_with_partners(const std::vector<double>& c,
                                         const std::vector<double>& d,
                                         dealii::Vector<double>& y) const
{
  if (!by_runs)
  {
    add_slices(slices.data(), slices.size(), column.data(), value.data(), sets, 1,
               c.data(), d.data(), Target::y_then_partners, y.begin(), nullptr);
    return;
  }
  // On each unknown, y += the sum over X first, then y += that over X'.
  const Sums s = sum_with_partners(c, d);
  add_and_clear(s.first_rows->data(), s.first_rows->size(), s.first, y.begin(), nullptr,
                nullptr);
  add_and_clear(s.second_rows->data(), s.second_rows->size(), s.second, y.begin(),
                nullptr, nullptr);
}
} // namespace pantocat
