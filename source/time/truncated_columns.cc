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
  for (unsigned int i = 0; i < n_dofs; ++i)
    start[i + 1] += start[i];
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
  const unsigned int n = start.size() - 1;
  for (unsigned int i = 0; i < n; ++i)
  {
    double s = 0.;
    for (std::size_t e = start[i]; e < start[i + 1]; ++e)
      s += value[e] * c[column[e]];
    y[i] += s;
  }
}
} // namespace pantocat
