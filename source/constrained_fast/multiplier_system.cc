#include <pantocat/base/input_error.h>
#include <pantocat/constrained_fast/multiplier_system.h>

#include <cmath>
#include <sstream>
#include <utility>

namespace pantocat
{
namespace
{
/// The largest system solved without the allocation of FullMatrix's pivot list.
constexpr unsigned int small_size = 4;

/**
 * x = A^-1 b for n <= small_size: Gaussian elimination with partial pivoting
 * on a copy in fixed-size arrays. The multiplier systems of a step of the
 * half-explicit method are 1 x 1 and 2 x 2 for one contact away from the
 * droppers (the fixed constraints are eliminated by their Schur complement):
 * FullMatrix::gauss_jordan() allocated its pivot list at every call, twice a
 * step. A zero pivot gives a non-finite x, reported as singular.
 */
void solve_small(const dealii::FullMatrix<double>& A, const dealii::Vector<double>& b,
                 dealii::Vector<double>& x)
{
  const unsigned int n = A.m();
  double a[small_size][small_size + 1];
  for (unsigned int i = 0; i < n; ++i)
  {
    for (unsigned int j = 0; j < n; ++j)
      a[i][j] = A(i, j);
    a[i][n] = b(i);
  }
  for (unsigned int j = 0; j < n; ++j)
  {
    unsigned int pivot = j;
    for (unsigned int i = j + 1; i < n; ++i)
      if (std::abs(a[i][j]) > std::abs(a[pivot][j]))
        pivot = i;
    if (pivot != j)
      for (unsigned int k = j; k <= n; ++k)
        std::swap(a[j][k], a[pivot][k]);
    for (unsigned int i = j + 1; i < n; ++i)
    {
      const double factor = a[i][j] / a[j][j];
      for (unsigned int k = j + 1; k <= n; ++k)
        a[i][k] -= factor * a[j][k];
    }
  }
  for (unsigned int i = n; i-- > 0;)
  {
    double sum = a[i][n];
    for (unsigned int k = i + 1; k < n; ++k)
      sum -= a[i][k] * x(k);
    x(i) = sum / a[i][i];
  }
}
} // namespace

void solve_multiplier_system(dealii::FullMatrix<double>& A,
                             const dealii::Vector<double>& b, dealii::Vector<double>& x,
                             const double t, const char* what)
{
  if (A.m() == 0)
    return;
  if (A.m() <= small_size)
    solve_small(A, b, x);
  else
  {
    A.gauss_jordan();
    A.vmult(x, b);
  }
  for (const double value : x)
    if (!std::isfinite(value))
    {
      std::ostringstream s;
      s << "the active constraints are linearly dependent at t = " << t << " s (" << what
        << ")";
      throw SimulationError(s.str());
    }
}
} // namespace pantocat
