#include <pantocat/analysis/static_equilibrium.h>
#include <pantocat/base/input_error.h>
#include <pantocat/lac/interleaved_columns.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <algorithm>
#include <cmath>
#include <set>

namespace pantocat
{
namespace
{
const char* const dependent_constraints =
    "static equilibrium: the active constraints are linearly dependent (G K^-1 G^T is "
    "singular)";
} // namespace

StaticEquilibriumSolver::StaticEquilibriumSolver(const SemiDiscreteSystem& system,
                                                 const double t,
                                                 const double column_budget)
    : system(system), states(system.n_constraints())
{
  const unsigned int m = states.size();
  for (unsigned int i = 0; i < m; ++i)
    system.constraints[i]->evaluate(t, states[i]);
  // A body that only its constraints hold (a stitch wire between its clamps):
  // K alone is singular, the saddle-point system is not.
  if (!system.stiffness_is_definite)
  {
    saddle_point = true;
    return;
  }
  try
  {
    K_inverse.factorize(system.stiffness, "stiffness matrix");
  }
  catch (const SimulationError&)
  {
    throw SimulationError("static equilibrium: the stiffness matrix is singular "
                          "(a body without tension, bending or support?)");
  }
  // K^-1 G^T is dense along a wire held only at its ends: m columns of n
  // cost O(n m) memory and time, quadratic in the number of spans, and the
  // inverse of S cubic. Within the budget they are formed here; beyond it
  // solve() factorises the saddle-point system instead.
  const double n = system.n_dofs();
  saddle_point = n * m > column_budget || m > max_dense_constraints;
  if (saddle_point)
    return;
  X.assign(m, dealii::Vector<double>(system.n_dofs()));
  schur.reinit(m, m);
  std::vector<unsigned int> all(m);
  for (unsigned int i = 0; i < m; ++i)
    all[i] = i;
  InterleavedColumns batch;
  batch.reinit(system.n_dofs());
  for (unsigned int first = 0; first < m; first += InterleavedColumns::width)
  {
    const unsigned int count = columns(all, first, batch);
    for (unsigned int c = 0; c < count; ++c)
    {
      for (unsigned int k = 0; k < m; ++k)
        schur(k, first + c) = batch.dot(states[k].G, c);
      for (unsigned int i = 0; i < system.n_dofs(); ++i)
        X[first + c](i) = batch(i, c);
    }
  }
}

unsigned int
StaticEquilibriumSolver::columns(const std::vector<unsigned int>& constraints,
                                 const unsigned int first,
                                 InterleavedColumns& batch) const
{
  constexpr unsigned int width = InterleavedColumns::width;
  const unsigned int count = std::min<unsigned int>(width, constraints.size() - first);
  batch.clear();
  for (unsigned int c = 0; c < count; ++c)
    batch.add_row(c, states[constraints[first + c]].G, 1.);
  K_inverse.solve_interleaved(batch.data(), width);
  return count;
}

void StaticEquilibriumSolver::factorize_saddle_point(
    const std::vector<bool>& active, const std::vector<unsigned int>& act) const
{
  if (active == factor_active)
    return;
  factor_active.clear(); // until `factor` holds this set's factor
  const unsigned int n = system.n_dofs(), m = act.size();
  dealii::DynamicSparsityPattern dsp(n + m, n + m);
  for (unsigned int i = 0; i < n; ++i)
    for (auto it = system.stiffness.begin(i); it != system.stiffness.end(i); ++it)
      dsp.add(i, it->column());
  for (unsigned int k = 0; k < m; ++k)
  {
    for (const unsigned int j : states[act[k]].G.index)
    {
      dsp.add(n + k, j);
      dsp.add(j, n + k);
    }
    dsp.add(n + k, n + k);
  }
  dealii::SparsityPattern pattern;
  pattern.copy_from(dsp);
  dealii::SparseMatrix<double> A(pattern);
  for (unsigned int i = 0; i < n; ++i)
    for (auto it = system.stiffness.begin(i); it != system.stiffness.end(i); ++it)
      A.add(i, it->column(), it->value());
  for (unsigned int k = 0; k < m; ++k)
  {
    const SparseRow& G = states[act[k]].G;
    for (std::size_t e = 0; e < G.size(); ++e)
    {
      A.add(n + k, G.index[e], G.value[e]);
      A.add(G.index[e], n + k, G.value[e]);
    }
    // An engaged spring: g + lambda / k = 0, the compliance on the diagonal.
    const Compliance& law = system.constraints[act[k]]->compliance();
    if (law.stiffness > 0.)
      A.add(n + k, n + k, -1. / law.stiffness);
  }
  try
  {
    factor.factorize(A, "saddle-point system", LinearSolverType::umfpack);
  }
  catch (const SimulationError&)
  {
    throw SimulationError(dependent_constraints);
  }
  factor_active = active;
}

void StaticEquilibriumSolver::solve_saddle_point(const std::vector<bool>& active,
                                                 const dealii::Vector<double>& load,
                                                 StaticEquilibrium& out) const
{
  std::vector<unsigned int> act;
  for (unsigned int i = 0; i < active.size(); ++i)
    if (active[i])
      act.push_back(i);
  factorize_saddle_point(active, act);
  const unsigned int n = system.n_dofs(), m = act.size();
  dealii::Vector<double> x(n + m);
  for (unsigned int i = 0; i < n; ++i)
    x(i) = load(i);
  for (unsigned int k = 0; k < m; ++k)
    x(n + k) = -states[act[k]].z;
  factor.solve(x);
  out.q.reinit(n);
  for (unsigned int i = 0; i < n; ++i)
    out.q(i) = x(i);
  out.multipliers.assign(states.size(), 0.);
  for (unsigned int k = 0; k < m; ++k)
  {
    if (!std::isfinite(x(n + k)))
      throw SimulationError(dependent_constraints);
    out.multipliers[act[k]] = -x(n + k);
  }
  out.gaps.resize(states.size());
  for (unsigned int i = 0; i < states.size(); ++i)
    out.gaps[i] = states[i].position_residual(out.q);
}

const dealii::FullMatrix<double>&
StaticEquilibriumSolver::S_inverse_of(const std::vector<bool>& active,
                                      const std::vector<unsigned int>& act) const
{
  if (active == inverse_active)
    return S_inverse;
  const unsigned int m = act.size();
  inverse_active.clear(); // until S_inverse holds this set's inverse
  S_inverse.reinit(m, m);
  for (unsigned int k = 0; k < m; ++k)
  {
    for (unsigned int l = 0; l < m; ++l)
      S_inverse(k, l) = schur(act[k], act[l]);
    // An engaged compliant constraint is a spring, lambda = -k g: the row
    // g + lambda/k = 0, the compliance 1/k on the diagonal of G K^-1 G^T.
    const Compliance& law = system.constraints[act[k]]->compliance();
    if (law.stiffness > 0.)
      S_inverse(k, k) += 1. / law.stiffness;
  }
  try
  {
    S_inverse.gauss_jordan(); // small and dense
  }
  catch (const dealii::ExceptionBase&)
  {
    throw SimulationError(dependent_constraints);
  }
  inverse_active = active;
  return S_inverse;
}

void StaticEquilibriumSolver::solve_with_active_set(const std::vector<bool>& active,
                                                    const dealii::Vector<double>& q_free,
                                                    StaticEquilibrium& out) const
{
  std::vector<unsigned int> act;
  for (unsigned int i = 0; i < active.size(); ++i)
    if (active[i])
      act.push_back(i);
  const unsigned int m = act.size();
  dealii::Vector<double> rhs(m), lambda(m);
  for (unsigned int k = 0; k < m; ++k)
    rhs(k) = -states[act[k]].position_residual(q_free);
  if (m > 0)
  {
    S_inverse_of(active, act).vmult(lambda, rhs);
    for (unsigned int k = 0; k < m; ++k)
      if (!std::isfinite(lambda(k)))
        throw SimulationError(dependent_constraints);
  }
  out.q = q_free;
  out.multipliers.assign(states.size(), 0.);
  for (unsigned int k = 0; k < m; ++k)
  {
    out.q.add(lambda(k), X[act[k]]);
    out.multipliers[act[k]] = lambda(k);
  }
  out.gaps.resize(states.size());
  for (unsigned int i = 0; i < states.size(); ++i)
    out.gaps[i] = states[i].position_residual(out.q);
}

int StaticEquilibriumSolver::constraint_to_switch(const StaticEquilibrium& s) const
{
  // Sec. 5.3: release the most negative multiplier, else add the most violated gap.
  const double gap_tolerance = 1e-12;
  int worst = -1;
  double worst_value = 0.;
  for (unsigned int i = 0; i < states.size(); ++i)
    if (system.constraints[i]->is_unilateral() && s.active[i] &&
        s.multipliers[i] < worst_value)
      worst = i, worst_value = s.multipliers[i];
  if (worst < 0)
    for (unsigned int i = 0; i < states.size(); ++i)
      if (!s.active[i] && s.gaps[i] < -gap_tolerance && s.gaps[i] < worst_value)
        worst = i, worst_value = s.gaps[i];
  return worst;
}

StaticEquilibrium
StaticEquilibriumSolver::solve(const dealii::Vector<double>& extra_load,
                               const std::vector<bool>& initial_active) const
{
  Assert(initial_active.size() == states.size(),
         dealii::ExcDimensionMismatch(initial_active.size(), states.size()));
  dealii::Vector<double> load(system.load);
  load += extra_load;
  dealii::Vector<double> q_free; // K^-1 (f + f_extra): the dense way's start
  if (!saddle_point)
  {
    q_free = load;
    K_inverse.solve(q_free);
  }

  StaticEquilibrium out;
  out.active = initial_active;
  // Bilateral constraints are always active.
  for (unsigned int i = 0; i < states.size(); ++i)
    if (!system.constraints[i]->is_unilateral())
      out.active[i] = true;
  std::set<std::vector<bool>> visited;
  for (unsigned int iteration = 1;; ++iteration)
  {
    if (!visited.insert(out.active).second)
      throw SimulationError("static equilibrium: the active set of the unilateral "
                            "constraints cycles after " +
                            std::to_string(iteration - 1) + " iterations");
    if (saddle_point)
      solve_saddle_point(out.active, load, out);
    else
      solve_with_active_set(out.active, q_free, out);
    out.active_set_iterations = iteration;
    const int worst = constraint_to_switch(out);
    if (worst < 0)
      return out;
    out.active[worst] = !out.active[worst];
  }
}

StaticEquilibrium
StaticEquilibriumSolver::solve(const dealii::Vector<double>& extra_load) const
{
  return solve(extra_load, std::vector<bool>(states.size(), true));
}

StaticEquilibrium solve_static_equilibrium(const SemiDiscreteSystem& system,
                                           const dealii::Vector<double>& extra_load,
                                           const double t)
{
  return StaticEquilibriumSolver(system, t).solve(extra_load);
}
} // namespace pantocat
