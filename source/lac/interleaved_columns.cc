#include <pantocat/lac/interleaved_columns.h>

#include <algorithm>

namespace pantocat
{
void InterleavedColumns::reinit(const unsigned int size)
{
  n = size;
  values.assign(static_cast<std::size_t>(n) * width, 0.);
}

void InterleavedColumns::clear()
{
  std::fill(values.begin(), values.end(), 0.);
}

void InterleavedColumns::add_row(const unsigned int k, const SparseRow& row,
                                 const double factor)
{
  for (std::size_t e = 0; e < row.size(); ++e)
    values[row.index[e] * width + k] += factor * row.value[e];
}

double InterleavedColumns::dot(const SparseRow& row, const unsigned int k) const
{
  double s = 0.;
  for (std::size_t e = 0; e < row.size(); ++e)
    s += row.value[e] * values[row.index[e] * width + k];
  return s;
}

std::array<double, InterleavedColumns::width>
InterleavedColumns::dots(const SparseRow& row) const
{
  std::array<double, width> s{};
  for (std::size_t e = 0; e < row.size(); ++e)
  {
    const double* x = values.data() + row.index[e] * width;
    for (unsigned int k = 0; k < width; ++k)
      s[k] += row.value[e] * x[k];
  }
  return s;
}

void InterleavedColumns::add_combination(const std::array<double, width>& c,
                                         dealii::Vector<double>& out) const
{
  const double* __restrict x = values.data();
  double* __restrict y = out.begin();
  for (unsigned int i = 0; i < n; ++i)
    y[i] += c[0] * x[width * i] + c[1] * x[width * i + 1] + c[2] * x[width * i + 2] +
            c[3] * x[width * i + 3];
}
} // namespace pantocat
