#include <pantocat/analysis/banded_eigenvalues.h>
#include <pantocat/base/input_error.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

extern "C"
{
  // LAPACK: selected eigenvalues of a banded symmetric-definite pencil.
  void dsbgvx_(const char* jobz, const char* range, const char* uplo, const int* n,
               const int* ka, const int* kb, double* ab, const int* ldab, double* bb,
               const int* ldbb, double* q, const int* ldq, const double* vl,
               const double* vu, const int* il, const int* iu, const double* abstol,
               int* m, double* w, double* z, const int* ldz, double* work, int* iwork,
               int* ifail, int* info);
  double dlamch_(const char* cmach);
  // LAPACK: Cholesky factorisation of a symmetric positive definite band matrix.
  void dpbtrf_(const char* uplo, const int* n, const int* kd, double* ab, const int* ldab,
               int* info);
}

namespace pantocat
{
unsigned int half_bandwidth(const dealii::SparseMatrix<double>& matrix)
{
  int b = 0;
  // Row by row: a deal.II iterator's row() is a binary search.
  for (unsigned int i = 0; i < matrix.m(); ++i)
    for (auto it = matrix.begin(i); it != matrix.end(i); ++it)
      if (it->value() != 0.)
        b = std::max(b, std::abs(static_cast<int>(i) - static_cast<int>(it->column())));
  return static_cast<unsigned int>(b);
}

namespace
{
/// Upper band storage (LAPACK 'U'): ab[(kd + i - j) + j * (kd + 1)] = A(i, j), i <= j.
std::vector<double> band_storage(const dealii::SparseMatrix<double>& A, const int kd)
{
  const int n = A.m();
  std::vector<double> ab((kd + 1) * n, 0.);
  for (int i = 0; i < n; ++i)
    for (auto it = A.begin(i); it != A.end(i); ++it)
    {
      const int j = it->column();
      if (i <= j && j - i <= kd)
        ab[(kd + i - j) + j * (kd + 1)] = it->value();
    }
  return ab;
}
/// LAPACK dpbtrf's info for the band matrix @p band (upper band storage,
/// overwritten by its factor): 0, or the order of the leading minor that is
/// not positive definite.
int cholesky_failure(std::vector<double>& band, const int n, const int kd)
{
  const int ld = kd + 1;
  int info = 0;
  dpbtrf_("U", &n, &kd, band.data(), &ld, &info);
  return info;
}

/// True if the band matrix sigma B - A (upper band storage) is positive
/// definite in floating point: its Cholesky factorisation runs to the end.
bool positive_definite(const double sigma, const std::vector<double>& a,
                       const std::vector<double>& b, const int n, const int kd,
                       std::vector<double>& work)
{
  for (std::size_t e = 0; e < work.size(); ++e)
    work[e] = sigma * b[e] - a[e];
  return cholesky_failure(work, n, kd) == 0;
}

/// What dsbgvx's @p info says went wrong for A x = lambda B x of size @p n.
std::string dsbgvx_failure(const int info, const int n)
{
  const std::string start =
      "LAPACK dsbgvx failed (info = " + std::to_string(info) + "): ";
  if (info > n)
    return start +
           "the second matrix of the generalized eigenproblem (M, or K for the "
           "smallest eigenvalue) is not positive definite in floating point "
           "(leading minor " +
           std::to_string(info - n) +
           "); check the masses, tensions and stiffnesses for values that are zero "
           "or of very different magnitudes";
  if (info > 0)
    return start + "the eigenvalue iteration did not converge; the matrices are badly "
                   "scaled (masses, tensions or stiffnesses of very different "
                   "magnitudes)";
  return start + (info < 0 ? "an argument was illegal" : "no eigenvalue was found");
}

/**
 * The largest eigenvalue of A x = lambda B x by LAPACK's dsbgvx: B's split
 * Cholesky factor, a reduction to tridiagonal form (O(n^2 kd)) and bisection
 * of the tridiagonal matrix, to full relative accuracy for the largest
 * eigenvalue also where A is ill-conditioned.
 */
double largest_by_reduction(const dealii::SparseMatrix<double>& A,
                            const dealii::SparseMatrix<double>& B)
{
  const int n = A.m();
  const int kd = std::max(half_bandwidth(A), half_bandwidth(B));
  std::vector<double> ab = band_storage(A, kd), bb = band_storage(B, kd);
  const int ld = kd + 1, one = 1;
  const double vl = 0., vu = 0.;
  const double abstol = 2. * dlamch_("S"); // most accurate bisection
  int m = 0, info = 0;
  std::vector<double> w(n), work(7 * n), q(1), z(1);
  std::vector<int> iwork(5 * n), ifail(n);
  dsbgvx_("N", "I", "U", &n, &kd, &kd, ab.data(), &ld, bb.data(), &ld, q.data(), &one,
          &vl, &vu, &n, &n, &abstol, &m, w.data(), z.data(), &one, work.data(),
          iwork.data(), ifail.data(), &info);
  if (info != 0 || m != 1)
    throw SimulationError(dsbgvx_failure(info, n));
  return w[0];
}
} // namespace

double largest_generalized_eigenvalue(const dealii::SparseMatrix<double>& A,
                                      const dealii::SparseMatrix<double>& B)
{
  const int n = A.m();
  const int kd = std::max(half_bandwidth(A), half_bandwidth(B));
  const std::vector<double> a = band_storage(A, kd), b = band_storage(B, kd);
  std::vector<double> work(a.size());
  // B positive definite: sigma B - A is then positive definite exactly for
  // sigma > lambda_max (Sylvester), and lambda_max is where that stops.
  work = b;
  if (const int info = cholesky_failure(work, n, kd); info != 0)
    throw SimulationError(
        "largest generalized eigenvalue: the second matrix (M, or K for the smallest "
        "eigenvalue) is not positive definite in floating point (leading minor " +
        std::to_string(info) +
        "); check the masses, tensions and stiffnesses for values that are zero or "
        "of very different magnitudes");
  // A lower bound: the Rayleigh quotients of the unit vectors, A_ii / B_ii.
  double lower = 0.;
  for (int i = 0; i < n; ++i)
    lower = std::max(lower, a[kd + static_cast<std::size_t>(i) * (kd + 1)] /
                                b[kd + static_cast<std::size_t>(i) * (kd + 1)]);
  if (!(lower > 0.))
    lower = std::numeric_limits<double>::min();
  double upper = 2. * lower;
  while (!positive_definite(upper, a, b, n, kd, work))
  {
    if (!std::isfinite(upper))
      throw SimulationError("largest generalized eigenvalue: no finite upper bound "
                            "(the matrices hold values that are not finite)");
    lower = upper;
    upper *= 2.;
  }
  // Bisection down to neighbouring doubles: about 53 factorisations, each
  // O(n kd^2), where a reduction to tridiagonal form would cost O(n^2 kd).
  for (;;)
  {
    const double middle = lower + 0.5 * (upper - lower);
    if (!(middle > lower && middle < upper))
      break;
    (positive_definite(middle, a, b, n, kd, work) ? upper : lower) = middle;
  }
  return upper;
}

double smallest_generalized_eigenvalue(const dealii::SparseMatrix<double>& A,
                                       const dealii::SparseMatrix<double>& B)
{
  return 1. / largest_by_reduction(B, A);
}
} // namespace pantocat
