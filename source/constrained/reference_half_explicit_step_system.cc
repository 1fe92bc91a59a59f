#include <pantocat/base/input_error.h>
#include <pantocat/constrained/reference_half_explicit_step_system.h>
#include <pantocat/constrained/unconstrained_prediction.h>

#include <deal.II/lac/lapack_full_matrix.h>

#include <cmath>
#include <sstream>

namespace pantocat
{
namespace
{
ConstrainedOperator::Definition smoothed_mass(const double h)
{
  ConstrainedOperator::Definition d;
  d.damping = 0.5 * h;
  d.what = "matrix M + dt/2 D";
  return d;
}

ConstrainedOperator::Definition mass_matrix()
{
  ConstrainedOperator::Definition d;
  d.what = "mass matrix M";
  return d;
}
} // namespace

ReferenceHalfExplicitStepSystem::ReferenceHalfExplicitStepSystem(
    const SemiDiscreteSystem& system, const double h)
    : HalfExplicitStepSystem(system, h),
      W(std::make_unique<ReferenceConstrainedOperator>(system, smoothed_mass(h))),
      M(system, mass_matrix())
{
}

void ReferenceHalfExplicitStepSystem::set_time_step(const double time_step)
{
  h = time_step;
  W = std::make_unique<ReferenceConstrainedOperator>(system, smoothed_mass(h));
}

void ReferenceHalfExplicitStepSystem::start(const Step& new_step)
{
  step = new_step;
}

void ReferenceHalfExplicitStepSystem::acceleration_level(
    const std::vector<unsigned int>& force_set, const std::vector<unsigned int>*)
{
  const dealii::Vector<double>&q = *step.q, &v = *step.v;
  dealii::Vector<double>& a = *step.a;
  std::vector<double>& lambda = *step.lambda;
  // (39), (41): W a* = f(t_n) - K q_n - D (v_{n-1} + v_n)/2 + G_c^T lambda_c.
  const unsigned int n = system.n_dofs();
  dealii::Vector<double> r(n), smoothed(v);
  system.load_at(step.t, a);
  system.stiffness.vmult(r, q);
  a -= r;
  smoothed += *step.v_previous;
  system.damping.vmult(r, smoothed);
  a.add(-0.5, r);
  for (unsigned int i = 0; i < system.n_constraints(); ++i)
    if (system.constraints[i]->is_compliant())
      (*step.at_n)[i].G.add_transpose_to(a, lambda[i]);
  W->apply_inverse(a);
  // g^(II) = G a + 2 G_t v + G_tt q + z_tt = 0 at t_n on the force set.
  std::vector<double> y(system.n_constraints(), 0.);
  for (const unsigned int i : force_set)
  {
    const ConstraintState& s = (*step.at_n)[i];
    y[i] = -(s.G.dot(a) + 2. * s.G_t.dot(v) + s.G_tt.dot(q) + s.z_tt);
  }
  W->set_rows(*step.at_n, step.t);
  if (!force_set.empty())
  {
    W->solve_multipliers(force_set, y, "acceleration level");
    W->add_columns(y, a);
  }
  for (unsigned int i = 0; i < system.n_constraints(); ++i)
    if (!system.constraints[i]->is_compliant())
      lambda[i] = y[i];
  for (unsigned int i = 0; i < n; ++i)
    predict_unconstrained(i, a[i], 2. * h, 0.5 * h, q.begin(), v.begin(),
                          step.v_previous->begin(), step.q_next->begin(),
                          step.v_next->begin());
}

const dealii::Vector<double>&
ReferenceHalfExplicitStepSystem::mass_column(const SparseRow& row, const unsigned int j,
                                             const bool constant)
{
  if (constant && constant_columns.count(j))
    return constant_columns[j];
  dealii::Vector<double> x(system.n_dofs());
  row.add_transpose_to(x, 1.);
  M.apply_inverse(x);
  if (!constant)
    return moving_column = std::move(x);
  return constant_columns[j] = std::move(x);
}

ReferenceHalfExplicitStepSystem::Corrections
ReferenceHalfExplicitStepSystem::corrections_of(const unsigned int j)
{
  // (40): q += M^-1 (h^2 G(t_n) + h G_t(t_{n+1/2}))^T eta + h M^-1 G(t_{n+1/2})^T mu,
  // v += 2 h M^-1 G(t_n)^T eta. A constraint with constant rows (G_t = 0)
  // has one column M^-1 G^T, solved once.
  const ConstraintState &sn = (*step.at_n)[j], &sh = (*step.at_half)[j];
  const bool constant = !system.constraints[j]->depends_on_time();
  Corrections c;
  c.v_eta = mass_column(sn.G, j, constant);
  c.v_eta *= 2. * h;
  c.q_eta = c.v_eta;
  c.q_eta *= 0.5 * h;
  c.q_mu = mass_column(sh.G, j, constant);
  c.q_mu *= h;
  if (!constant)
    c.q_eta.add(h, mass_column(sh.G_t, j, false));
  return c;
}

void ReferenceHalfExplicitStepSystem::position_level(const std::vector<unsigned int>& set)
{
  dealii::Vector<double>&q = *step.q_next, &v = *step.v_next;
  const std::vector<ConstraintState>& s1 = *step.at_next;
  const unsigned int p = set.size();
  std::vector<Corrections> columns;
  for (const unsigned int j : set)
    columns.push_back(corrections_of(j));
  // Unknowns (eta_j, mu_j), equations g_i = 0 and dg_i/dt = 0 at t_{n+1}.
  dealii::LAPACKFullMatrix<double> E(2 * p, 2 * p);
  dealii::Vector<double> x(2 * p);
  for (unsigned int e = 0; e < p; ++e)
  {
    const ConstraintState& r = s1[set[e]];
    for (unsigned int u = 0; u < p; ++u)
    {
      const Corrections& c = columns[u];
      E(e, u) = r.G.dot(c.q_eta);
      E(e, p + u) = r.G.dot(c.q_mu);
      E(p + e, u) = r.G.dot(c.v_eta) + r.G_t.dot(c.q_eta);
      E(p + e, p + u) = r.G_t.dot(c.q_mu);
    }
    x(e) = -(r.G.dot(q) + r.z);
    x(p + e) = -(r.G.dot(v) + r.G_t.dot(q) + r.z_t);
  }
  if (p > 0)
  {
    std::ostringstream singular;
    singular << "the active constraints are linearly dependent at t = " << step.t + h
             << " s (position/velocity level)";
    try
    {
      E.compute_lu_factorization();
    }
    catch (const std::exception&)
    {
      throw SimulationError(singular.str());
    }
    E.solve(x);
    for (unsigned int u = 0; u < 2 * p; ++u)
      if (!std::isfinite(x(u)))
        throw SimulationError(singular.str());
  }
  for (unsigned int u = 0; u < p; ++u)
  {
    q.add(x(u), columns[u].q_eta);
    q.add(x(p + u), columns[u].q_mu);
    v.add(x(u), columns[u].v_eta);
  }
  for (unsigned int i = 0; i < system.n_constraints(); ++i)
    (*step.gaps)[i] = s1[i].position_residual(q);
}
} // namespace pantocat
