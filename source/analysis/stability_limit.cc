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

namespace
{
/// The compliant constraints' rows at a time, and which of them meet each unknown.
struct CompliantRows
{
  std::vector<unsigned int> constraint; ///< the system's index of each
  std::vector<ConstraintState> rows;
  CompressedRows flat;
  RowsByColumn on_unknown;

  CompliantRows(const SemiDiscreteSystem& system, const double t)
  {
    for (unsigned int i = 0; i < system.n_constraints(); ++i)
      if (system.constraints[i]->is_compliant())
        constraint.push_back(i);
    rows.resize(constraint.size());
    for (std::size_t k = 0; k < constraint.size(); ++k)
    {
      system.constraints[constraint[k]]->evaluate(t, rows[k], 0);
      flat.push_back(rows[k].G);
    }
    on_unknown.build(flat, system.n_dofs());
  }
  double stiffness(const SemiDiscreteSystem& system, const unsigned int k) const
  {
    return system.constraints[constraint[k]]->compliance().stiffness;
  }
};

/**
 * visit(k, reach, dot) for each compliant row k of @p c with the column
 * x = M^-1 G_k^T: the rows it reaches, and dot(l) = G_l x for any compliant
 * row l. For a diagonal M the column lives on the row's own unknowns; for a
 * banded one it is solved locally, four columns at a time
 * (SparseDirectSolver::solve_local(): it decays away from the row), so all of
 * them cost O(m) and not O(n m).
 */
template <typename Visit>
void for_each_mass_column(const SemiDiscreteSystem& system, const CompliantRows& c,
                          const Visit& visit)
{
  if (system.mass_is_diagonal)
  {
    dealii::Vector<double> x(system.n_dofs());
    for (std::size_t k = 0; k < c.constraint.size(); ++k)
    {
      const SparseRow& G = c.rows[k].G;
      RowRanges reach;
      for (std::size_t e = 0; e < G.size(); ++e)
      {
        x[G.index[e]] += G.value[e] / system.mass.diag_element(G.index[e]);
        reach.push_back({static_cast<int>(G.index[e]), static_cast<int>(G.index[e]) + 1});
      }
      visit(k, reach, [&](const unsigned int l) { return c.rows[l].G.dot(x); });
      for (const unsigned int u : G.index)
        x[u] = 0.;
    }
    return;
  }
  SparseDirectSolver mass_inverse; // banded Cholesky (or UMFPACK)
  mass_inverse.factorize(system.mass, "mass matrix M");
  LocalColumns columns;
  columns.reinit(system.n_dofs());
  constexpr unsigned int width = LocalColumns::width;
  for (std::size_t first = 0; first < c.constraint.size(); first += width)
  {
    const std::size_t count = std::min<std::size_t>(width, c.constraint.size() - first);
    columns.clear();
    for (std::size_t j = 0; j < count; ++j)
      columns.add_row(j, c.rows[first + j].G, 1.);
    columns.solve(mass_inverse);
    for (std::size_t j = 0; j < count; ++j)
      visit(first + j, columns.reach(),
            [&](const unsigned int l) { return columns.dot(c.rows[l].G, j); });
  }
}

/**
 * sum_l sqrt(k_c k_l) |G_l x| over the compliant constraints l whose rows
 * meet the unknowns @p reach of the column x = M^-1 G_c^T (@p dot(l) =
 * G_l x): row c of Gershgorin's bound.
 */
template <typename Dot>
double coupling_row_sum(const SemiDiscreteSystem& system, const CompliantRows& c,
                        const unsigned int k, const RowRanges& reach, const Dot& dot,
                        std::vector<char>& seen)
{
  std::vector<unsigned int> met;
  for (const RowRange& r : reach)
    for (int u = r.first; u < r.last; ++u)
      for (unsigned int e = c.on_unknown.start[u]; e < c.on_unknown.start[u + 1]; ++e)
        if (!seen[c.on_unknown.row[e]])
        {
          seen[c.on_unknown.row[e]] = 1;
          met.push_back(c.on_unknown.row[e]);
        }
  double sum = 0.;
  for (const unsigned int l : met)
  {
    sum += std::sqrt(c.stiffness(system, k) * c.stiffness(system, l)) * std::abs(dot(l));
    seen[l] = 0;
  }
  return sum;
}
} // namespace

double compliant_frequency_bound(const SemiDiscreteSystem& system, const double t)
{
  // The springs add M^-1 sum_i k_i G_i^T G_i to M^-1 K; its non-zero
  // eigenvalues are those of A = Kc^1/2 G M^-1 G^T Kc^1/2 (Kc = diag k_i),
  // bounded by Gershgorin: max_i sum_j sqrt(k_i k_j) |G_i M^-1 G_j^T|. Only
  // the constraints whose rows meet the column M^-1 G_i^T count, so the
  // bound is that of the densest neighbourhood, not of the whole line.
  const CompliantRows c(system, t);
  std::vector<char> seen(c.constraint.size(), 0);
  double bound = 0.;
  for_each_mass_column(
      system, c,
      [&](const unsigned int k, const RowRanges& reach, const auto& dot)
      { bound = std::max(bound, coupling_row_sum(system, c, k, reach, dot, seen)); });
  return bound;
}

std::vector<double> compliant_mass_factors(const SemiDiscreteSystem& system,
                                           const double t)
{
  std::vector<double> factor(system.n_constraints(), 0.);
  const CompliantRows c(system, t);
  for_each_mass_column(system, c,
                       [&](const unsigned int k, const RowRanges&, const auto& dot)
                       { factor[c.constraint[k]] = dot(k); });
  return factor;
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
