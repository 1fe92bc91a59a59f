#include <pantocat/base/input_error.h>
#include <pantocat/lac/sparse_direct_solver.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

extern "C"
{
  // LAPACK: Cholesky factorisation of a symmetric positive definite band matrix.
  void dpbtrf_(const char* uplo, const int* n, const int* kd, double* ab, const int* ldab,
               int* info);
}

namespace pantocat
{
namespace
{
/// Banded storage pays off only for narrow bands.
constexpr int max_banded_bandwidth = 16;
} // namespace

bool SparseDirectSolver::try_banded_cholesky(const dealii::SparseMatrix<double>& A)
{
  n = A.m();
  kd = 0;
  for (auto it = A.begin(); it != A.end(); ++it)
    if (it->value() != 0.)
    {
      const int d =
          std::abs(static_cast<int>(it->row()) - static_cast<int>(it->column()));
      kd = std::max(kd, d);
      if (kd > max_banded_bandwidth)
        return false;
      // Cholesky needs symmetry (up to round-off of the assembly).
      if (it->row() < it->column())
      {
        const double other = A.el(it->column(), it->row());
        if (std::abs(it->value() - other) >
            1e-12 * (std::abs(it->value()) + std::abs(other)))
          return false;
      }
    }
  const int ld = kd + 1;
  band.assign(static_cast<std::size_t>(ld) * n, 0.);
  for (auto it = A.begin(); it != A.end(); ++it)
  {
    const int i = it->row(), j = it->column();
    if (i <= j)
      band[(kd + i - j) + static_cast<std::size_t>(j) * ld] = it->value();
  }
  int info = 0;
  dpbtrf_("U", &n, &kd, band.data(), &ld, &info);
  if (info != 0) // not positive definite
    return false;
  reciprocal.resize(n);
  for (int i = 0; i < n; ++i)
    reciprocal[i] = 1. / band[kd + static_cast<std::size_t>(i) * ld];
  return true;
}

void SparseDirectSolver::factorize(const dealii::SparseMatrix<double>& matrix,
                                   const std::string& what)
{
  banded = try_banded_cholesky(matrix);
  if (banded)
    return;
  band.clear();
  try
  {
    umfpack.initialize(matrix);
  }
  catch (const std::exception&)
  {
    throw SimulationError("the " + what + " is singular and cannot be factorised");
  }
}

void SparseDirectSolver::solve(dealii::Vector<double>& x) const
{
  if (!banded)
  {
    umfpack.solve(x);
    return;
  }
  // A = U^T U: forward U^T y = b, then backward U x = y. U(i, j), i <= j <= i + kd,
  // sits at band[(kd + i - j) + j (kd + 1)].
  const int ld = kd + 1;
  double* __restrict y = x.begin();
  const double* __restrict u = band.data();
  for (int j = 0; j < n; ++j)
  {
    double s = y[j];
    const double* column = u + static_cast<std::size_t>(j) * ld + kd - j;
    for (int i = std::max(0, j - kd); i < j; ++i)
      s -= column[i] * y[i];
    y[j] = s * reciprocal[j];
  }
  for (int i = n - 1; i >= 0; --i)
  {
    double s = y[i];
    for (int j = i + 1; j <= std::min(n - 1, i + kd); ++j)
      s -= u[(kd + i - j) + static_cast<std::size_t>(j) * ld] * y[j];
    y[i] = s * reciprocal[i];
  }
}
} // namespace pantocat
