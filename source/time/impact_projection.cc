#include <pantocat/time/impact_projection.h>

namespace pantocat
{
ImpactProjection::ImpactProjection(const SemiDiscreteSystem& system,
                                   ConstrainedOperator& mass)
    : system(system), mass(mass)
{
}

template <typename Residual>
std::vector<double>
ImpactProjection::project_level(const std::vector<ConstraintState>& rows,
                                const std::vector<unsigned int>& holding, const double t,
                                Residual residual, dealii::Vector<double>& target)
{
  mass.set_rows(rows, t);
  std::vector<double> multipliers;
  mass.project(holding, residual, target, multipliers, "impact projection");
  multipliers.resize(system.n_constraints(), 0.);
  return multipliers;
}

ImpactProjection::Result
ImpactProjection::project(const std::vector<ConstraintState>& rows,
                          const std::vector<unsigned int>& holding, const double t,
                          const std::vector<double>& lambda, const double dt,
                          dealii::Vector<double>& q, dealii::Vector<double>& v)
{
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

} // namespace pantocat
