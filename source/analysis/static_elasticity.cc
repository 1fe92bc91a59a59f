#include <pantocat/analysis/static_elasticity.h>
#include <pantocat/analysis/static_equilibrium.h>

#include <algorithm>
#include <chrono>
#include <limits>

namespace pantocat
{
namespace
{
/// The droppers (1-based) slack in @p loaded and taut in @p unloaded.
std::vector<unsigned int> slackened_droppers(const std::vector<unsigned int>& droppers,
                                             const StaticEquilibrium& unloaded,
                                             const StaticEquilibrium& loaded)
{
  std::vector<unsigned int> slack;
  for (unsigned int j = 0; j < droppers.size(); ++j)
    if (unloaded.active[droppers[j]] && !loaded.active[droppers[j]])
      slack.push_back(j + 1);
  return slack;
}
} // namespace

ElasticityFigures elasticity_figures(const double force, const std::vector<double>& e)
{
  ElasticityFigures f;
  f.force = force;
  if (e.empty())
    return f;
  const auto [lo, hi] = std::minmax_element(e.begin(), e.end());
  f.minimum = *lo;
  f.maximum = *hi;
  double sum = 0.;
  for (const double v : e)
    sum += v;
  f.mean = sum / e.size();
  const double scale = f.maximum + f.minimum;
  f.uniformity = scale != 0. ? (f.maximum - f.minimum) / scale
                             : std::numeric_limits<double>::quiet_NaN();
  return f;
}

std::vector<double> StaticElasticity::elasticity(const unsigned int f) const
{
  std::vector<double> e;
  for (const double u : uplift[f])
    e.push_back(1000. * u / forces[f]);
  return e;
}

ElasticityFigures StaticElasticity::figures(const unsigned int f) const
{
  return elasticity_figures(forces[f], elasticity(f));
}

std::vector<double> span_points(const CatenaryParameters& catenary,
                                const unsigned int span, const unsigned int n)
{
  const std::vector<double> supports = catenary.support_positions();
  const double a = supports[span - 1], b = supports[span];
  std::vector<double> x(n);
  for (unsigned int i = 0; i < n; ++i)
    x[i] = a + (b - a) * i / (n - 1);
  x.back() = b; // exactly on the support
  return x;
}

StaticElasticity static_elasticity(const SemiDiscreteSystem& catenary,
                                   const CatenaryDiscretisation& space,
                                   const std::vector<unsigned int>& dropper_indices,
                                   const ElasticityParameters& parameters)
{
  const auto start = std::chrono::steady_clock::now();
  StaticElasticity result;
  result.span = parameters.span;
  result.forces = parameters.forces;
  result.x = span_points(space.catenary_parameters(), parameters.span, parameters.points);
  const unsigned int n_forces = result.forces.size(), n_points = result.x.size();
  result.uplift.assign(n_forces, std::vector<double>(n_points, 0.));
  result.slackened.assign(n_forces, std::vector<std::vector<unsigned int>>(n_points));

  const StaticEquilibriumSolver solver(catenary);
  const dealii::Vector<double> no_load(catenary.n_dofs());
  const StaticEquilibrium unloaded = solver.solve(no_load);
  dealii::Vector<double> load(catenary.n_dofs());
  for (unsigned int i = 0; i < n_points; ++i)
  {
    const SparseRow H = wire_point_row(space, catenary, Wire::contact_wire, result.x[i]);
    if (H.size() == 0)
      continue; // a pinned end of the section
    for (unsigned int f = 0; f < n_forces; ++f)
    {
      load = 0.;
      H.add_transpose_to(load, result.forces[f]);
      const StaticEquilibrium loaded = solver.solve(load, unloaded.active);
      result.uplift[f][i] = H.dot(loaded.q) - H.dot(unloaded.q);
      result.slackened[f][i] = slackened_droppers(dropper_indices, unloaded, loaded);
      ++result.solves;
      result.active_set_iterations += loaded.active_set_iterations;
    }
  }
  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}
} // namespace pantocat
