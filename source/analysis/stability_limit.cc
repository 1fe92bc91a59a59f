#include <pantocat/analysis/banded_eigenvalues.h>
#include <pantocat/analysis/half_explicit_step_map.h>
#include <pantocat/analysis/stability_limit.h>
#include <pantocat/lac/local_columns.h>
#include <pantocat/lac/sparse_direct_solver.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <algorithm>
#include <cmath>
#include <limits>
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

std::vector<double> compliant_mass_factors(const SemiDiscreteSystem& system,
                                           const double t)
{
  std::vector<double> factor(system.n_constraints(), 0.);
  std::vector<unsigned int> compliant;
  for (unsigned int i = 0; i < system.n_constraints(); ++i)
    if (system.constraints[i]->is_compliant())
      compliant.push_back(i);
  if (compliant.empty())
    return factor;
  std::vector<ConstraintState> rows(compliant.size());
  for (std::size_t k = 0; k < compliant.size(); ++k)
    system.constraints[compliant[k]]->evaluate(t, rows[k], 0);
  if (system.mass_is_diagonal)
  {
    for (std::size_t k = 0; k < compliant.size(); ++k)
      for (std::size_t e = 0; e < rows[k].G.size(); ++e)
        factor[compliant[k]] += rows[k].G.value[e] * rows[k].G.value[e] /
                                system.mass.diag_element(rows[k].G.index[e]);
    return factor;
  }
  // M^-1 G_i^T decays away from the row's entries: local solves, four
  // columns at a time, cost O(reach) each instead of O(n).
  SparseDirectSolver mass_inverse; // banded Cholesky (or UMFPACK)
  mass_inverse.factorize(system.mass, "mass matrix M");
  LocalColumns columns;
  columns.reinit(system.n_dofs());
  constexpr unsigned int width = LocalColumns::width;
  for (std::size_t first = 0; first < compliant.size(); first += width)
  {
    const std::size_t count = std::min<std::size_t>(width, compliant.size() - first);
    columns.clear();
    for (std::size_t c = 0; c < count; ++c)
      columns.add_row(c, rows[first + c].G, 1.);
    columns.solve(mass_inverse);
    for (std::size_t c = 0; c < count; ++c)
      factor[compliant[first + c]] = columns.dot(rows[first + c].G, c);
  }
  return factor;
}

double compliant_frequency_bound(const SemiDiscreteSystem& system, const double t)
{
  const std::vector<double> GMG = compliant_mass_factors(system, t);
  double bound = 0.;
  for (unsigned int i = 0; i < system.n_constraints(); ++i)
    if (system.constraints[i]->is_compliant())
      bound += system.constraints[i]->compliance().stiffness * GMG[i]; // k G M^-1 G^T
  return bound;
}

ExplicitDampingLimit explicit_damping_limit(const SemiDiscreteSystem& system,
                                            const double t)
{
  ExplicitDampingLimit l;
  const std::vector<double> GMG = compliant_mass_factors(system, t);
  double largest = 0.;
  for (unsigned int i = 0; i < system.n_constraints(); ++i)
  {
    const double cGMG = system.constraints[i]->compliance().damping * GMG[i];
    if (system.constraints[i]->is_compliant() && cGMG > largest)
    {
      largest = cGMG;
      l.constraint = i;
      l.damping = system.constraints[i]->compliance().damping;
      l.mass_factor = GMG[i];
    }
  }
  l.step = largest > 0. ? 2. / largest : std::numeric_limits<double>::infinity();
  return l;
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
    l.unstable = l.critical;
    l.growth_unstable = growth;
    if (k == 10)
    {
      // No stable step down to upper / 2^11: the caller names the cause.
      l.critical = l.allowed = 0.;
      return l;
    }
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
