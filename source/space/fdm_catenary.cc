#include <pantocat/space/fdm_catenary.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <algorithm>
#include <cmath>

namespace pantocat
{
FdmCatenary::FdmCatenary(const CatenaryParameters& catenary,
                         const DiscretisationParameters& discretisation)
    : CatenaryDiscretisation(catenary, discretisation)
{
}

void FdmCatenary::initialize_operator(const Wire wire, const bool with_bending,
                                      BlockOperator& op) const
{
  const unsigned int n = n_dofs(wire);
  const unsigned int bandwidth = with_bending ? 2 : 1;
  op.name = wire_block_name(wire);
  dealii::DynamicSparsityPattern dsp(n, n);
  for (unsigned int i = 0; i < n; ++i)
    for (unsigned int j = (i >= bandwidth ? i - bandwidth : 0);
         j <= std::min(n - 1, i + bandwidth); ++j)
      dsp.add(i, j);
  op.sparsity->copy_from(dsp);
  op.reinit_matrices(n);
  op.mass_is_diagonal = true;
}

void FdmCatenary::add_terms(const Wire wire, const WireTerms& p, BlockOperator& op) const
{
  const unsigned int n = n_dofs(wire);
  const double dx = cell_size();
  // Tension: -T w'' -> (T/dx) tridiag(-1, 2, -1).
  const double t = p.tension / dx;
  // Bending: EI w'''' -> (EI/dx^3) Q^2, Q = tridiag(1, -2, 1) with the
  // boundary values q''_0 = q''_{N+1} = 0 of (3).
  const bool beam = p.bending != 0.;
  const double b = beam ? p.bending / (dx * dx * dx) : 0.;
  const auto add = [&](const unsigned int i, const unsigned int j, const double value)
  {
    if (value != 0.)
      op.stiffness.add(i, j, value);
  };
  for (unsigned int i = 0; i < n; ++i)
  {
    if (p.mass != 0.)
      op.mass.add(i, i, p.mass * dx);
    if (p.damping != 0.)
      op.damping.add(i, i, p.damping * dx);
    const bool first_or_last = (i == 0 || i + 1 == n);
    if (n > 1)
      add(i, i, 2. * t + b * (first_or_last ? 5. : 6.));
    if (i + 1 < n)
    {
      add(i, i + 1, -t - 4. * b);
      add(i + 1, i, -t - 4. * b);
    }
    if (beam && i + 2 < n)
    {
      add(i, i + 2, b);
      add(i + 2, i, b);
    }
    op.load(i) -= p.weight * dx;
  }
  if (n == 1) // a single unknown: Q = (-2), Q^2 = (4)
    add(0, 0, 2. * t + 4. * b);
}

void FdmCatenary::interpolate(const Wire wire, const std::function<double(double)>& w,
                              const std::function<double(double)>& /*dw*/,
                              dealii::Vector<double>& q) const
{
  q.reinit(n_dofs(wire));
  for (unsigned int i = 0; i < q.size(); ++i)
    q(i) = w((i + 1) * cell_size());
}

unsigned int FdmCatenary::control_volume_node(const double x) const
{
  const double s = x / cell_size() + 0.5; // node i when i <= s < i + 1
  const double nearest = std::round(s);
  const double snapped = std::abs(s - nearest) < 1e-9 * std::max(1., s) ? nearest : s;
  return static_cast<unsigned int>(std::floor(snapped));
}

SparseRow FdmCatenary::point_row(const Wire /*wire*/, const double x) const
{
  SparseRow row;
  const unsigned int i = control_volume_node(x);
  if (i >= 1 && i <= n_intervals() - 1)
    row.add(i - 1, 1.);
  return row;
}

void FdmCatenary::load_row(const double x_c, const unsigned int k, SparseRow& row) const
{
  row.clear();
  const double dx = cell_size();
  const unsigned int n = n_intervals() - 1;
  if (discretisation.load_shape == LoadShape::point)
  {
    // A point load spread to the two neighbouring nodes by the hat functions.
    const double s = x_c / dx;
    const unsigned int left = std::min(static_cast<unsigned int>(std::floor(s)), n);
    const double xi = s - left;
    const double value[2] = {1. - xi, xi};
    const double slope[2] = {-1. / dx, 1. / dx};
    for (unsigned int m = 0; m < 2; ++m)
    {
      const unsigned int node = left + m;
      if (node < 1 || node > n)
        continue;
      // int delta^{(k)}(x - x_c) phi(x) dx = (-1)^k phi^{(k)}(x_c)
      const double v = k == 0 ? value[m] : (k == 1 ? -slope[m] : 0.);
      row.add(node - 1, v);
    }
    return;
  }
  // Control volumes [x_{i-1/2}, x_{i+1/2}] that meet [x_c - eps, x_c + eps].
  const double eps = delta.epsilon();
  const int first = std::max(1, static_cast<int>(std::floor((x_c - eps) / dx + 0.5)));
  const int last =
      std::min(static_cast<int>(n), static_cast<int>(std::floor((x_c + eps) / dx + 0.5)));
  // The antiderivative (k = 0) or derivative k - 1 at the edges of the
  // control volumes: each edge is shared by two neighbours, evaluated once.
  const auto at_edge = [&](const double xi)
  { return k == 0 ? delta.integral_up_to(xi) : delta.derivative(xi, k - 1); };
  double left = at_edge((first - 0.5) * dx - x_c);
  for (int i = first; i <= last; ++i)
  {
    const double right = at_edge((i + 0.5) * dx - x_c);
    row.add(i - 1, right - left);
    left = right;
  }
}
} // namespace pantocat
