#include <pantocat/analysis/static_equilibrium.h>
#include <pantocat/base/input_error.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparse_direct.h>

#include <cmath>
#include <set>

namespace pantocat
{
namespace
{
/// Solves for the multipliers of the constraints in @p active; fills q and lambda.
void solve_with_active_set(const dealii::SparseDirectUMFPACK& K_inverse,
                           const SemiDiscreteSystem& system,
                           const std::vector<ConstraintState>& states,
                           const std::vector<bool>& active,
                           const dealii::Vector<double>& q_free, StaticEquilibrium& out)
{
  const unsigned int n = q_free.size();
  std::vector<unsigned int> act;
  for (unsigned int i = 0; i < active.size(); ++i)
    if (active[i])
      act.push_back(i);
  const unsigned int m = act.size();
  // X = K^{-1} G_A^T, column by column.
  std::vector<dealii::Vector<double>> X(m, dealii::Vector<double>(n));
  for (unsigned int k = 0; k < m; ++k)
  {
    states[act[k]].G.add_transpose_to(X[k], 1.);
    K_inverse.solve(X[k]);
  }
  dealii::FullMatrix<double> S(m, m);
  dealii::Vector<double> rhs(m), lambda(m);
  for (unsigned int k = 0; k < m; ++k)
  {
    for (unsigned int l = 0; l < m; ++l)
      S(k, l) = states[act[k]].G.dot(X[l]);
    // An engaged compliant constraint is a spring, lambda = -k g: the row
    // g + lambda/k = 0, the compliance 1/k on the diagonal of G K^-1 G^T.
    const Compliance& law = system.constraints[act[k]]->compliance();
    if (law.stiffness > 0.)
      S(k, k) += 1. / law.stiffness;
    rhs(k) = -states[act[k]].position_residual(q_free);
  }
  if (m > 0)
  {
    S.gauss_jordan(); // small and dense
    S.vmult(lambda, rhs);
    for (unsigned int k = 0; k < m; ++k)
      if (!std::isfinite(lambda(k)))
        throw SimulationError("static equilibrium: the active constraints are linearly "
                              "dependent (G K^-1 G^T is singular)");
  }
  out.q = q_free;
  out.multipliers.assign(states.size(), 0.);
  for (unsigned int k = 0; k < m; ++k)
  {
    out.q.add(lambda(k), X[k]);
    out.multipliers[act[k]] = lambda(k);
  }
  out.gaps.resize(states.size());
  for (unsigned int i = 0; i < states.size(); ++i)
    out.gaps[i] = states[i].position_residual(out.q);
}
} // namespace

StaticEquilibrium solve_static_equilibrium(const SemiDiscreteSystem& system,
                                           const dealii::Vector<double>& extra_load,
                                           const double t)
{
  dealii::SparseDirectUMFPACK K_inverse;
  try
  {
    K_inverse.initialize(system.stiffness);
  }
  catch (...)
  {
    throw SimulationError("static equilibrium: the stiffness matrix is singular "
                          "(a body without tension, bending or support?)");
  }
  dealii::Vector<double> q_free(system.load);
  q_free += extra_load;
  K_inverse.solve(q_free);

  std::vector<ConstraintState> states(system.n_constraints());
  for (unsigned int i = 0; i < states.size(); ++i)
    system.constraints[i]->evaluate(t, states[i]);

  StaticEquilibrium out;
  out.active.assign(states.size(), true);
  std::set<std::vector<bool>> visited;
  const double gap_tolerance = 1e-12;
  for (unsigned int iteration = 1;; ++iteration)
  {
    if (!visited.insert(out.active).second)
      throw SimulationError("static equilibrium: the active set of the unilateral "
                            "constraints cycles after " +
                            std::to_string(iteration - 1) + " iterations");
    try
    {
      solve_with_active_set(K_inverse, system, states, out.active, q_free, out);
    }
    catch (const dealii::ExceptionBase&)
    {
      throw SimulationError("static equilibrium: the active constraints are linearly "
                            "dependent (G K^-1 G^T is singular)");
    }
    out.active_set_iterations = iteration;
    // Sec. 5.3: release the most negative multiplier, else add the most violated gap.
    int worst = -1;
    double worst_value = 0.;
    for (unsigned int i = 0; i < states.size(); ++i)
      if (system.constraints[i]->is_unilateral() && out.active[i] &&
          out.multipliers[i] < worst_value)
        worst = i, worst_value = out.multipliers[i];
    if (worst < 0)
      for (unsigned int i = 0; i < states.size(); ++i)
        if (!out.active[i] && out.gaps[i] < -gap_tolerance && out.gaps[i] < worst_value)
          worst = i, worst_value = out.gaps[i];
    if (worst < 0)
      return out;
    out.active[worst] = !out.active[worst];
  }
}
} // namespace pantocat
