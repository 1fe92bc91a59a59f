#include <pantocat/system/energy_functional.h>

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
}

double QuadraticForm::operator()(const dealii::Vector<double>& x) const
{
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
