#include <pantocat/analysis/banded_eigenvalues.h>
#include <pantocat/base/input_error.h>

#include <algorithm>
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
}

namespace pantocat
{
unsigned int half_bandwidth(const dealii::SparseMatrix<double>& matrix)
{
  unsigned int b = 0;
  for (auto it = matrix.begin(); it != matrix.end(); ++it)
    if (it->value() != 0.)
      b = std::max<unsigned int>(b, it->row() > it->column() ? it->row() - it->column()
                                                             : it->column() - it->row());
  return b;
}

namespace
{
/// Upper band storage (LAPACK 'U'): ab[(kd + i - j) + j * (kd + 1)] = A(i, j), i <= j.
std::vector<double> band_storage(const dealii::SparseMatrix<double>& A, const int kd)
{
  const int n = A.m();
  std::vector<double> ab((kd + 1) * n, 0.);
  for (auto it = A.begin(); it != A.end(); ++it)
  {
    const int i = it->row(), j = it->column();
    if (i <= j && j - i <= kd)
      ab[(kd + i - j) + j * (kd + 1)] = it->value();
  }
  return ab;
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
} // namespace

double largest_generalized_eigenvalue(const dealii::SparseMatrix<double>& A,
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

double smallest_generalized_eigenvalue(const dealii::SparseMatrix<double>& A,
                                       const dealii::SparseMatrix<double>& B)
{
  return 1. / largest_generalized_eigenvalue(B, A);
}
} // namespace pantocat
