#include <pantocat/system/energy_functional.h>

#include <algorithm>
#include <cstring>

namespace pantocat
{
QuadraticForm::QuadraticForm(const dealii::SparseMatrix<double>& A)
    : diagonal(A.m(), 0.), row_start(1, 0)
{
  for (unsigned int i = 0; i < A.m(); ++i)
  {
    for (auto entry = A.begin(i); entry != A.end(i); ++entry)
    {
      const unsigned int j = entry->column();
      if (j == i)
        diagonal[i] = entry->value();
      else if (j > i)
      {
        const double w = entry->value() + A.el(j, i);
        if (w != 0.)
        {
          column.push_back(j);
          weight.push_back(w);
        }
      }
      else if (!A.get_sparsity_pattern().exists(j, i) && entry->value() != 0.)
      {
        // a_ij (j < i) without an entry (j, i), whose row would have taken
        // the pair: the pair's weight is a_ij alone.
        column.push_back(j);
        weight.push_back(entry->value());
      }
    }
    row_start.push_back(column.size());
  }
  store_as_band();
}

/**
 * Moves the pairs into the band of their offsets when the band is at least
 * half full and has at most 16 offsets (QuadraticForm's comment); keeps the
 * compact rows otherwise.
 */
void QuadraticForm::store_as_band()
{
  const std::size_t n = diagonal.size();
  std::vector<unsigned int> found;
  for (std::size_t i = 0; i < n; ++i)
    for (unsigned int k = row_start[i]; k < row_start[i + 1]; ++k)
    {
      const unsigned int o = column[k] - i;
      if (std::find(found.begin(), found.end(), o) == found.end())
      {
        found.push_back(o);
        if (found.size() > 16)
          return;
      }
    }
  std::size_t places = 0;
  for (const unsigned int o : found)
    places += n - o;
  if (places > 2 * column.size())
    return;
  std::sort(found.begin(), found.end());
  by_offset.assign(found.size(), {});
  for (std::size_t k = 0; k < found.size(); ++k)
    by_offset[k].assign(n - found[k], 0.);
  for (std::size_t i = 0; i < n; ++i)
    for (unsigned int k = row_start[i]; k < row_start[i + 1]; ++k)
    {
      const std::size_t o =
          std::lower_bound(found.begin(), found.end(), column[k] - i) - found.begin();
      by_offset[o][i] += weight[k]; // a pair appears once; += keeps the sum exact
    }
  offsets = std::move(found);
  band = true;
  row_start.clear();
  column.clear();
  weight.clear();
}

namespace
{
/**
 * sum_i w_i x_i y_i over @p n entries: eight partial sums in two four-double
 * vectors (GCC's vector extensions), compiled for AVX2 beside the baseline.
 */
__attribute__((target_clones("avx2", "default"))) double
weighted_products(const double* __restrict w, const double* __restrict x,
                  const double* __restrict y, const std::size_t n)
{
  using Quad = double __attribute__((vector_size(32)));
  Quad s0 = {0., 0., 0., 0.}, s1 = {0., 0., 0., 0.};
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8)
  {
    Quad w0, w1, x0, x1, y0, y1;
    std::memcpy(&w0, w + i, sizeof w0);
    std::memcpy(&w1, w + i + 4, sizeof w1);
    std::memcpy(&x0, x + i, sizeof x0);
    std::memcpy(&x1, x + i + 4, sizeof x1);
    std::memcpy(&y0, y + i, sizeof y0);
    std::memcpy(&y1, y + i + 4, sizeof y1);
    s0 += w0 * x0 * y0;
    s1 += w1 * x1 * y1;
  }
  const Quad s = s0 + s1;
  double sum = (s[0] + s[1]) + (s[2] + s[3]);
  for (; i < n; ++i)
    sum += w[i] * x[i] * y[i];
  return sum;
}
} // namespace

double QuadraticForm::operator()(const dealii::Vector<double>& x) const
{
  if (banded())
  {
    const double* p = x.begin();
    double sum = weighted_products(diagonal.data(), p, p, diagonal.size());
    for (std::size_t k = 0; k < offsets.size(); ++k)
      sum +=
          weighted_products(by_offset[k].data(), p, p + offsets[k], by_offset[k].size());
    return sum;
  }
  // Four partial sums over the rows: the additions of one chain wait on
  // each other, those of four chains do not.
  const double* __restrict p = x.begin();
  const unsigned int n = diagonal.size();
  const auto row = [&](const unsigned int i)
  {
    double r = diagonal[i] * p[i];
    for (unsigned int k = row_start[i]; k < row_start[i + 1]; ++k)
      r += weight[k] * p[column[k]];
    return p[i] * r;
  };
  double sum[4] = {0., 0., 0., 0.};
  unsigned int i = 0;
  for (; i + 4 <= n; i += 4)
    for (unsigned int c = 0; c < 4; ++c)
      sum[c] += row(i + c);
  for (; i < n; ++i)
    sum[0] += row(i);
  return (sum[0] + sum[1]) + (sum[2] + sum[3]);
}

EnergyFunctional::EnergyFunctional(const SemiDiscreteSystem& system)
    : system(system), mass(system.mass), stiffness(system.stiffness)
{
}

double EnergyFunctional::operator()(const dealii::Vector<double>& q,
                                    const dealii::Vector<double>& v, const double t) const
{
  return 0.5 * mass(v) + 0.5 * stiffness(q) + system.potential_of_loads_and_springs(q, t);
}
} // namespace pantocat
