#include <pantocat/analysis/banded_eigenvalues.h>
#include <pantocat/analysis/half_explicit_step_map.h>
#include <pantocat/analysis/stability_limit.h>
#include <pantocat/lac/sparse_direct_solver.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

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
  return std::sqrt(omega2 + compliant_frequency_bound(system));
}

double compliant_frequency_bound(const SemiDiscreteSystem& system, const double t)
{
  if (!system.has_compliant_constraints())
    return 0.;
  SparseDirectSolver mass_inverse; // banded Cholesky (or UMFPACK)
  if (!system.mass_is_diagonal)
    mass_inverse.factorize(system.mass, "mass matrix M");
  double bound = 0.;
  ConstraintState row;
  dealii::Vector<double> column(system.n_dofs());
  for (const auto& c : system.constraints)
    if (c->is_compliant())
    {
      c->evaluate(t, row, 0);
      // k G M^-1 G^T: the one non-zero eigenvalue of M^-1 k G^T G.
      double GMG = 0.;
      if (system.mass_is_diagonal)
        for (std::size_t e = 0; e < row.G.size(); ++e)
          GMG +=
              row.G.value[e] * row.G.value[e] / system.mass.diag_element(row.G.index[e]);
      else
      {
        column = 0.;
        row.G.add_transpose_to(column, 1.);
        mass_inverse.solve(column);
        GMG = row.G.dot(column);
      }
      bound += c->compliance().stiffness * GMG;
    }
  return bound;
}

std::string compliant_stiffness_note(const SemiDiscreteSystem& system)
{
  const Constraint* stiffest = nullptr;
  for (const auto& c : system.constraints)
    if (c->is_compliant() &&
        (!stiffest || c->compliance().stiffness > stiffest->compliance().stiffness))
      stiffest = c.get();
  if (!stiffest)
    return "";
  std::ostringstream s;
  s << ", including the compliant constraints (stiffest: '" << stiffest->name()
    << "', k = " << stiffest->compliance().stiffness
    << " N/m), explicit forces of this method that raise omega_max by k G M^-1 G^T";
  return s.str();
}
bool has_moving_constraints(const SemiDiscreteSystem& system,
                            const std::vector<bool>& active)
{
  for (unsigned int i = 0; i < system.n_constraints(); ++i)
    if (i < active.size() && active[i] && system.constraints[i]->depends_on_time())
      return true;
  return false;
}

namespace
{
bool stable(const SemiDiscreteSystem& system, const std::vector<bool>& active,
            const double dt, const double t0, const StepLimitOptions& options,
            double& growth)
{
  growth = growth_per_step(system, active, dt, t0, options.steps);
  return growth <= 1. + options.growth_tolerance;
}
} // namespace

bool half_explicit_step_allowed(const SemiDiscreteSystem& system,
                                const std::vector<bool>& active, const double dt,
                                const double t0, const StepLimitOptions& options,
                                double* growth)
{
  double g = 0.;
  const bool ok = stable(system, active, dt / options.margin, t0, options, g);
  if (growth)
    *growth = g;
  return ok;
}

HalfExplicitStepLimit half_explicit_step_limit(const SemiDiscreteSystem& system,
                                               const std::vector<bool>& active,
                                               const double upper, const double t0,
                                               const StepLimitOptions& options)
{
  HalfExplicitStepLimit l;
  double growth = 0.;
  l.unstable = upper;
  ++l.tests;
  if (stable(system, active, upper, t0, options, growth))
    throw std::runtime_error("half_explicit_step_limit: the upper step is stable");
  l.growth_unstable = growth;
  l.critical = 0.5 * upper;
  for (unsigned int k = 0;; ++k)
  {
    ++l.tests;
    if (stable(system, active, l.critical, t0, options, growth))
      break;
    if (k == 10)
      throw std::runtime_error("half_explicit_step_limit: no stable step above " +
                               std::to_string(l.critical) + " s");
    l.unstable = l.critical;
    l.growth_unstable = growth;
    l.critical *= 0.5;
  }
  while (l.unstable - l.critical > options.relative_accuracy * l.critical)
  {
    const double mid = 0.5 * (l.critical + l.unstable);
    ++l.tests;
    if (stable(system, active, mid, t0, options, growth))
      l.critical = mid;
    else
    {
      l.unstable = mid;
      l.growth_unstable = growth;
    }
  }
  l.allowed = options.margin * l.critical;
  return l;
}
} // namespace pantocat
