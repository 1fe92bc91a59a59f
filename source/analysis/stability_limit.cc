#include <pantocat/analysis/banded_eigenvalues.h>
#include <pantocat/analysis/stability_limit.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <algorithm>
#include <cmath>

namespace pantocat
{
double largest_circular_frequency(const SemiDiscreteSystem& system)
{
  double omega2 = 0.;
  for (const DofBlock& b : system.blocks)
  {
    dealii::DynamicSparsityPattern dsp(b.size, b.size);
    for (unsigned int i = 0; i < b.size; ++i)
      for (auto it = system.sparsity->begin(b.first + i);
           it != system.sparsity->end(b.first + i); ++it)
        dsp.add(i, it->column() - b.first);
    dealii::SparsityPattern pattern;
    pattern.copy_from(dsp);
    dealii::SparseMatrix<double> M(pattern), K(pattern);
    for (unsigned int i = 0; i < b.size; ++i)
      for (auto it = system.sparsity->begin(b.first + i);
           it != system.sparsity->end(b.first + i); ++it)
      {
        const unsigned int j = it->column();
        M.set(i, j - b.first, system.mass(b.first + i, j));
        K.set(i, j - b.first, system.stiffness(b.first + i, j));
      }
    omega2 = std::max(omega2, largest_generalized_eigenvalue(K, M));
  }
  return std::sqrt(omega2);
}
} // namespace pantocat
