#include <pantocat/time/truncated_columns.h>

#include <cmath>

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

void TruncatedColumns::initialize(const std::vector<SparseRow>& columns,
                                  const unsigned int n_dofs)
{
  m = columns.size();
  start.assign(n_dofs + 1, 0);
  for (const SparseRow& c : columns)
    for (const unsigned int i : c.index)
      ++start[i + 1];
  reached.clear();
  for (unsigned int i = 0; i < n_dofs; ++i)
  {
    if (start[i + 1] > 0)
      reached.push_back(i);
    start[i + 1] += start[i];
  }
  column.resize(start.back());
  value.resize(start.back());
  std::vector<std::size_t> next(start.begin(), start.end() - 1);
  for (unsigned int l = 0; l < m; ++l)
    for (std::size_t k = 0; k < columns[l].size(); ++k)
    {
      const std::size_t e = next[columns[l].index[k]]++;
      column[e] = l;
      value[e] = columns[l].value[k];
    }
}

void TruncatedColumns::row_products(const SparseRow& g, std::vector<double>& out) const
{
  out.assign(m, 0.);
  for (std::size_t k = 0; k < g.size(); ++k)
  {
    const unsigned int i = g.index[k];
    for (std::size_t e = start[i]; e < start[i + 1]; ++e)
      out[column[e]] += g.value[k] * value[e];
  }
}

void TruncatedColumns::add(const std::vector<double>& c, dealii::Vector<double>& y) const
{
  // An unknown no column reaches would take y_i += 0: skipped (the same
  // value; y_i = -0 stays -0 instead of becoming +0).
  for (const unsigned int i : reached)
  {
    double s = 0.;
    for (std::size_t e = start[i]; e < start[i + 1]; ++e)
      s += value[e] * c[column[e]];
    y[i] += s;
  }
}

void TruncatedColumns::add(const std::vector<double>& c, dealii::Vector<double>& y,
                           const std::vector<double>& d, dealii::Vector<double>& z) const
{
  for (const unsigned int i : reached)
  {
    double s = 0., t = 0.;
    for (std::size_t e = start[i]; e < start[i + 1]; ++e)
    {
      s += value[e] * c[column[e]];
      t += value[e] * d[column[e]];
    }
    y[i] += s;
    z[i] += t;
  }
}
} // namespace pantocat
