#include <pantocat/base/input_error.h>
#include <pantocat/time/multiplier_system.h>

#include <cmath>
#include <sstream>

namespace pantocat
{
void solve_multiplier_system(dealii::FullMatrix<double>& A,
                             const dealii::Vector<double>& b, dealii::Vector<double>& x,
                             const double t, const char* what)
{
  if (A.m() == 0)
    return;
  A.gauss_jordan();
  A.vmult(x, b);
  for (const double value : x)
    if (!std::isfinite(value))
    {
      std::ostringstream s;
      s << "the active constraints are linearly dependent at t = " << t << " s (" << what
        << ")";
      throw SimulationError(s.str());
    }
}

void solve_bordered_batched(
    const std::function<void(const std::vector<dealii::Vector<double>*>&)>& solve_fixed,
    std::vector<dealii::Vector<double>>& B, const std::vector<dealii::Vector<double>>& C,
    dealii::FullMatrix<double>& D, dealii::Vector<double>& r, dealii::Vector<double>& s,
    const double t, const char* what)
{
  const bool has_fixed = r.size() > 0;
  const unsigned int p = s.size();
  if (has_fixed)
  {
    // A border column that no fixed row sees (an FDM contact away from every
    // dropper node) needs no solve: A^-1 0 = 0.
    std::vector<dealii::Vector<double>*> batch{&r};
    for (auto& b : B)
      if (b.linfty_norm() != 0.)
        batch.push_back(&b);
    solve_fixed(batch);
  }
  if (p == 0)
    return;
  dealii::Vector<double> rhs(s);
  if (has_fixed)
    for (unsigned int k = 0; k < p; ++k)
    {
      rhs(k) -= C[k] * r;
      for (unsigned int l = 0; l < p; ++l)
        D(k, l) -= C[k] * B[l];
    }
  solve_multiplier_system(D, rhs, s, t, what);
  if (has_fixed)
    for (unsigned int l = 0; l < p; ++l)
      r.add(-s(l), B[l]);
}
} // namespace pantocat
