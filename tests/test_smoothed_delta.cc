// The smoothed load delta_eps of Sec. 4.1 and the contact rows F_w(t) of (33)
// (FEM) and Sec. 4.3 (FDM): exact moments for any x_p, including positions
// where x_p or x_p +- eps cross grid vertices.
#include <pantocat/space/fdm_catenary.h>
#include <pantocat/space/fem_catenary.h>
#include <pantocat/space/smoothed_delta.h>

#include <deal.II/base/quadrature_lib.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace pantocat;

namespace
{
/// Gauss integral of f over [a, b] split at the knots of delta_eps centred at 0.
template <typename F>
double integrate_on_pieces(F f, double eps)
{
  const dealii::QGauss<1> gauss(6);
  double sum = 0.;
  for (const auto& [a, b] : {std::pair{-eps, 0.}, std::pair{0., eps}})
    for (unsigned int q = 0; q < gauss.size(); ++q)
      sum += (b - a) * gauss.weight(q) * f(a + (b - a) * gauss.point(q)[0]);
  return sum;
}

DiscretisationParameters grid(SpaceMethod method, unsigned int n_intervals)
{
  DiscretisationParameters d;
  d.method = method;
  d.n_intervals = n_intervals;
  return d;
}

/// Positions where x_c or x_c +- eps hit vertices (h = 0.04, eps = 0.2), and generic
/// ones.
const std::vector<double> contact_positions = {2.0, 2.02,        2.04,         2.2,
                                               5.5, 7.123456789, 10.0 + 1e-13, 17.8};
} // namespace

TEST(SmoothedDelta, IsANormalisedNonNegativeC1Spline)
{
  const double eps = 0.2;
  const SmoothedDelta delta(eps);
  // Unit integral (Sec. 4.1), exact with Gauss rules on the two cubic pieces.
  EXPECT_NEAR(integrate_on_pieces([&](double x) { return delta.value(x); }, eps), 1.,
              1e-14);
  // Second moment: int xi^2 delta_eps = 2 eps^2 / 15 (closed form).
  EXPECT_NEAR(integrate_on_pieces([&](double x) { return x * x * delta.value(x); }, eps),
              2. * eps * eps / 15., 1e-15);
  EXPECT_DOUBLE_EQ(delta.derivative(0., 1), 0.); // delta'(0) = 0
  for (double xi = -0.25; xi <= 0.25; xi += 0.01)
    EXPECT_GE(delta.value(xi), 0.);
  // C1 at the knots: value and slope continuous at -eps, 0, eps.
  for (const double knot : delta.knots())
    for (unsigned int k = 0; k < 2; ++k)
      EXPECT_NEAR(delta.derivative(knot - 1e-12, k), delta.derivative(knot + 1e-12, k),
                  1e-8);
  // The antiderivative matches the quadrature of the density.
  EXPECT_NEAR(delta.integral_up_to(0.), 0.5, 1e-15);
  // Gauss on [-0.05, 0] and [0, 0.07], where the density is a cubic: exact.
  const dealii::QGauss<1> gauss(2);
  double integral = 0.;
  for (const auto& [a, b] : {std::pair{-0.05, 0.}, std::pair{0., 0.07}})
    for (unsigned int q = 0; q < gauss.size(); ++q)
      integral +=
          (b - a) * gauss.weight(q) * delta.value(a + (b - a) * gauss.point(q)[0]);
  EXPECT_NEAR(delta.integral_up_to(0.07) - delta.integral_up_to(-0.05), integral, 1e-15);
}

TEST(SmoothedDelta, DerivativesMatchFiniteDifferences)
{
  const SmoothedDelta delta(0.2);
  const double d = 1e-6;
  for (double xi = -0.19; xi < 0.19; xi += 0.0231)
  {
    EXPECT_NEAR((delta.value(xi + d) - delta.value(xi - d)) / (2 * d),
                delta.derivative(xi, 1), 1e-4);
    EXPECT_NEAR((delta.derivative(xi + d, 1) - delta.derivative(xi - d, 1)) / (2 * d),
                delta.derivative(xi, 2), 1e-3);
  }
}

TEST(ContactRow, FemIntegratesPolynomialsExactlyForAnyContactPosition)
{
  // The Hermite space contains 1, x, x^2, x^3, so F_w . (interpolant of p)
  // equals int delta_eps(x - x_c) p(x) dx exactly when the cells are split at
  // x_c and x_c +- eps (33). Unsplit QGauss(2) would miss by ~1e-4.
  CatenaryParameters catenary;
  const FemCatenary fem(catenary, grid(SpaceMethod::fem, 500));
  const auto& dofs = fem.dof_handler(Wire::contact_wire);
  const double eps = 0.2, m2 = 2. * eps * eps / 15.;
  auto interpolant = [&](auto p, auto dp)
  {
    dealii::Vector<double> u(dofs.n_dofs());
    for (const auto& cell : dofs.active_cell_iterators())
      for (unsigned int v = 0; v < 2; ++v)
      {
        u(cell->vertex_dof_index(v, 0)) = p(cell->vertex(v)[0]);
        u(cell->vertex_dof_index(v, 1)) = dp(cell->vertex(v)[0]);
      }
    return u;
  };
  const auto one = interpolant([](double) { return 1.; }, [](double) { return 0.; });
  const auto x1 = interpolant([](double x) { return x; }, [](double) { return 1.; });
  const auto x2 =
      interpolant([](double x) { return x * x; }, [](double x) { return 2 * x; });
  const auto x3 =
      interpolant([](double x) { return x * x * x; }, [](double x) { return 3 * x * x; });
  SparseRow r0, r1, r2;
  for (const double xc : contact_positions)
  {
    fem.full_load_row(xc, 0, r0);
    fem.full_load_row(xc, 1, r1);
    fem.full_load_row(xc, 2, r2);
    EXPECT_NEAR(r0.dot(one), 1., 1e-14) << "x_c = " << xc;
    const double moment3 = xc * xc * xc + 3. * xc * m2;
    EXPECT_NEAR(r0.dot(x3), moment3, 1e-14 * moment3) << "x_c = " << xc;
    // int delta' (x - x_c) x dx = -1, int delta''(x - x_c) x^2 dx = 2.
    EXPECT_NEAR(r1.dot(x1), -1., 1e-11) << "x_c = " << xc;
    EXPECT_NEAR(r1.dot(one), 0., 1e-11) << "x_c = " << xc;
    EXPECT_NEAR(r2.dot(x2), 2., 1e-9) << "x_c = " << xc;
  }
}

TEST(ContactRow, FdmRowSumsToOneAndItsDerivativesAreConsistent)
{
  // FDM row (Sec. 4.3): the control-volume integrals of delta_eps sum to 1.
  CatenaryParameters catenary;
  const FdmCatenary fdm(catenary, grid(SpaceMethod::fdm, 500));
  SparseRow r0, r1;
  for (const double xc : contact_positions)
  {
    fdm.load_row(xc, 0, r0);
    fdm.load_row(xc, 1, r1);
    EXPECT_NEAR(r0.sum(), 1., 1e-14) << "x_c = " << xc;
    EXPECT_NEAR(r1.sum(), 0., 1e-11) << "x_c = " << xc;
  }
}

TEST(ContactRow, TimeDerivativeRowsMatchFiniteDifferencesInXc)
{
  // d/dx_c r_0 = -r_1 and d/dx_c r_1 = -r_2 (row by row), for FEM and FDM:
  // these rows feed the hidden constraints, so an error here breaks (38).
  CatenaryParameters catenary;
  for (const SpaceMethod method : {SpaceMethod::fem, SpaceMethod::fdm})
  {
    const auto d = create_catenary_discretisation(catenary, grid(method, 200));
    const unsigned int n = d->n_dofs(Wire::contact_wire);
    const double h = 1e-6;
    for (const double xc : {3.0137, 9.95})
      for (unsigned int k = 0; k < 2; ++k)
      {
        SparseRow plus, minus, next;
        d->load_row(xc + h, k, plus);
        d->load_row(xc - h, k, minus);
        d->load_row(xc, k + 1, next);
        dealii::Vector<double> fd(n), exact(n);
        plus.add_transpose_to(fd, 0.5 / h);
        minus.add_transpose_to(fd, -0.5 / h);
        next.add_transpose_to(exact, -1.);
        const double scale = exact.linfty_norm();
        fd -= exact;
        EXPECT_LT(fd.linfty_norm(), 1e-5 * scale)
            << to_string(method) << " k = " << k << " x_c = " << xc;
      }
  }
}
