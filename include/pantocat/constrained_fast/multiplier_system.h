#pragma once

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <vector>

namespace pantocat
{
/**
 * Solves the small dense system of the multipliers (lambda, eta, mu) of the
 * active constraints: x = A^{-1} b (A may be overwritten). Throws SimulationError
 * naming time @p t and @p what if A is singular (linearly dependent active
 * constraints). Does nothing for an empty active set.
 */
void solve_multiplier_system(dealii::FullMatrix<double>& A,
                             const dealii::Vector<double>& b, dealii::Vector<double>& x,
                             double t, const char* what);

/**
 * Solves the bordered multiplier system [A B; C D] [x; y] = [r; s] by block
 * elimination: A is the (sparse, factorised once per active set) block of the
 * constraints with constant rows, the border B, C, D that of the p moving
 * ones (the contacts): x0 = A^-1 r, Z = A^-1 B, (D - C Z) y = s - C x0,
 * x = x0 - Z y. @p B holds the columns of B (becomes Z), @p C the rows of C;
 * on return @p r holds x and @p s holds y.
 *
 * @p solve_fixed(xs) applies A^-1 in place to each vector of xs: r and the
 * border columns that are not zero (a border column that no fixed row sees,
 * an FDM contact away from every dropper node, needs no solve), so a solver
 * can substitute them side by side (FixedConstraintSchur). @p rhs and
 * @p batch are workspaces: a caller that keeps them allocates nothing.
 */
template <typename SolveFixed>
void solve_bordered(const SolveFixed& solve_fixed, std::vector<dealii::Vector<double>>& B,
                    const std::vector<dealii::Vector<double>>& C,
                    dealii::FullMatrix<double>& D, dealii::Vector<double>& r,
                    dealii::Vector<double>& s, dealii::Vector<double>& rhs,
                    std::vector<dealii::Vector<double>*>& batch, const double t,
                    const char* what)
{
  const bool has_fixed = r.size() > 0;
  const unsigned int p = s.size();
  if (has_fixed)
  {
    batch.assign(1, &r);
    for (auto& b : B)
      if (b.linfty_norm() != 0.)
        batch.push_back(&b);
    solve_fixed(batch);
  }
  if (p == 0)
    return;
  rhs = s;
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
