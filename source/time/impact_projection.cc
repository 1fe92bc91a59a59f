#include <pantocat/time/impact_projection.h>
#include <pantocat/time/multiplier_system.h>

#include <deal.II/lac/full_matrix.h>

namespace pantocat
{
ImpactProjection::ImpactProjection(const SemiDiscreteSystem& system,
                                   const MassInverse& mass_inverse)
    : system(system), mass_inverse(mass_inverse)
{
  position.assign(system.n_constraints(), -1);
  for (unsigned int i = 0; i < system.n_constraints(); ++i)
    if (!system.constraints[i]->is_compliant() &&
        !system.constraints[i]->depends_on_time())
    {
      position[i] = fixed.size();
      fixed.push_back(i);
    }
  keep.assign(fixed.size(), false);
}

template <typename Residual>
std::vector<double>
ImpactProjection::project_level(const std::vector<ConstraintState>& rows,
                                const std::vector<unsigned int>& holding, const double t,
                                Residual residual, dealii::Vector<double>& target)
{
  const unsigned int n = system.n_dofs(), mF = fixed.size();
  std::fill(keep.begin(), keep.end(), false);
  std::vector<unsigned int> moving_in;
  for (const unsigned int i : holding)
    if (position[i] >= 0)
      keep[position[i]] = true;
    else
      moving_in.push_back(i);
  const unsigned int p = moving_in.size();
  // Columns M^-1 G^T of the moving constraints.
  std::vector<dealii::Vector<double>> U(p, dealii::Vector<double>(n));
  for (unsigned int c = 0; c < p; ++c)
  {
    rows[moving_in[c]].G.add_transpose_to(U[c], 1.);
    mass_inverse.apply(U[c]);
  }
  fixed_mass.select(keep);
  dealii::Vector<double> x(mF), y(p);
  for (unsigned int k = 0; k < mF; ++k)
    if (keep[k])
      x(k) = -residual(fixed[k]);
  std::vector<dealii::Vector<double>> B(p, dealii::Vector<double>(mF));
  dealii::FullMatrix<double> D(p, p);
  for (unsigned int c = 0; c < p; ++c)
  {
    for (unsigned int k = 0; k < mF; ++k)
      if (keep[k])
        B[c](k) = rows[fixed[k]].G.dot(U[c]);
    for (unsigned int r = 0; r < p; ++r)
      D(r, c) = rows[moving_in[r]].G.dot(U[c]);
    y(c) = -residual(moving_in[c]);
  }
  std::vector<dealii::Vector<double>> C(B);
  dealii::Vector<double> rhs;
  std::vector<dealii::Vector<double>*> batch;
  solve_bordered([&](const auto& xs) { fixed_mass.solve(xs); }, B, C, D, x, y, rhs, batch,
                 t, "impact projection");
  std::vector<double> multipliers(system.n_constraints(), 0.), factors(mF, 0.);
  for (unsigned int k = 0; k < mF; ++k)
    if (keep[k])
      multipliers[fixed[k]] = factors[k] = x(k);
  fixed_mass.add_columns(factors, target);
  for (unsigned int c = 0; c < p; ++c)
  {
    multipliers[moving_in[c]] = y(c);
    target.add(y(c), U[c]);
  }
  return multipliers;
}

ImpactProjection::Result
ImpactProjection::project(const std::vector<ConstraintState>& rows,
                          const std::vector<unsigned int>& holding, const double t,
                          const std::vector<double>& lambda, const double dt,
                          dealii::Vector<double>& q, dealii::Vector<double>& v)
{
  if (!fixed_ready)
  {
    std::vector<const SparseRow*> G;
    for (const unsigned int i : fixed)
      G.push_back(&rows[i].G);
    fixed_mass.initialize(G, mass_inverse, system.n_dofs(),
                          "matrix G M^-1 G^T of the fixed constraints (impacts)");
    fixed_ready = true;
  }
  project_level(
      rows, holding, t,
      [&](const unsigned int i) { return rows[i].position_residual(q); }, q);
  const dealii::Vector<double> v_before(v);
  std::vector<unsigned int> set = holding;
  Result r;
  for (;;)
  {
    r.impulse = project_level(
        rows, set, t,
        [&](const unsigned int i) { return rows[i].velocity_residual(q, v); }, v);
    double scale = 0.;
    for (const double P : r.impulse)
      scale = std::max(scale, std::abs(P));
    // Pulling over the step beyond round-off of the largest impulse: it
    // separates.
    std::vector<unsigned int> keep_set;
    bool separates = false;
    for (const unsigned int i : set)
      if (system.constraints[i]->is_unilateral() &&
          r.impulse[i] + dt * lambda[i] < -1e-9 * scale)
      {
        r.separated.push_back(i);
        separates = true;
      }
      else
        keep_set.push_back(i);
    if (!separates)
      break;
    set.swap(keep_set);
    v = v_before;
  }
  // Round-off of a unilateral impulse is not reported as a pull.
  for (unsigned int i = 0; i < r.impulse.size(); ++i)
    if (system.constraints[i]->is_unilateral() && r.impulse[i] + dt * lambda[i] < 0.)
      r.impulse[i] = -dt * lambda[i];
  return r;
}

void ImpactProjection::restart_acceleration(
    const std::vector<ConstraintState>& rows, const std::vector<unsigned int>& holding,
    const double t, const dealii::Vector<double>& q, const dealii::Vector<double>& v,
    const std::vector<double>& lambda, dealii::Vector<double>& a)
{
  // a_free = M^-1 (f - K q - D v + G_c^T lambda_c), the compliant forces included.
  const unsigned int n = system.n_dofs();
  dealii::Vector<double> work(n);
  a.reinit(n, true);
  system.load_at(t, a);
  system.stiffness.vmult(work, q);
  a -= work;
  system.damping.vmult(work, v);
  a -= work;
  for (unsigned int i = 0; i < rows.size(); ++i)
    if (system.constraints[i]->is_compliant() && lambda[i] != 0.)
      rows[i].G.add_transpose_to(a, lambda[i]);
  mass_inverse.apply(a);
  project_level(
      rows, holding, t,
      [&](const unsigned int i)
      {
        const ConstraintState& r = rows[i];
        return r.G.dot(a) + 2. * r.G_t.dot(v) + r.G_tt.dot(q) + r.z_tt;
      },
      a);
}
} // namespace pantocat
