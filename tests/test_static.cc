// Static problems: string and tensioned beam under point and uniform loads
// against closed forms; the paper's initial catenary (Fig. 5) with droppers.
#include "support/catenary_system_builder.h"
#include "support/closed_forms.h"
#include <pantocat/analysis/static_equilibrium.h>
#include <pantocat/base/input_error.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace pantocat;

namespace
{
DiscretisationParameters grid(SpaceMethod method, unsigned int n)
{
  DiscretisationParameters d;
  d.method = method;
  d.n_intervals = n;
  return d;
}

/// Solves one wire alone (no droppers) with gravity g and a point load P at a.
struct SingleWire
{
  SingleWire(SpaceMethod method, unsigned int n, Wire wire, double g, double P, double a)
  {
    p.gravity = g;
    d = create_catenary_discretisation(p, grid(method, n));
    BlockOperator op;
    d->assemble(wire, op);
    system.set_blocks({&op});
    dealii::Vector<double> load(op.size());
    d->point_row(wire, a).add_transpose_to(load, P);
    q = solve_static_equilibrium(system, load).q;
    this->wire = wire;
  }
  double w(double x) const
  {
    return d->displacement(wire, q, x) - (wire == Wire::carrier ? p.support_height : 0.);
  }
  CatenaryParameters p;
  std::unique_ptr<CatenaryDiscretisation> d;
  SemiDiscreteSystem system;
  dealii::Vector<double> q;
  Wire wire;
};

/// EI w'''' - T w'' = -q0 with simple supports (closed form).
double beam_uniform_load(double x, double q0, double L, double T, double EI)
{
  const double k = std::sqrt(T / EI);
  return -q0 / (2. * T) * x * (L - x) -
         q0 / (T * k * k) * (std::cosh(k * (x - L / 2.)) / std::cosh(k * L / 2.) - 1.);
}

double max_error(const SingleWire& s, const std::function<double(double)>& exact)
{
  double e = 0.;
  for (const double x : s.d->grid_points())
    e = std::max(e, std::abs(s.w(x) - exact(x)));
  return e;
}
} // namespace

TEST(StaticString, PointLoadIsNodallyExactForFemAndFdm)
{
  // -T w'' = P delta(x - a): the tent w = P x (L-a)/(T L) (x < a). Linear
  // elements and the 3-point difference scheme are nodally exact: round-off only.
  const double P = 100., a = 6.;
  for (const SpaceMethod method : {SpaceMethod::fem, SpaceMethod::fdm})
  {
    SingleWire s(method, 100, Wire::carrier, 0., P, a);
    const double L = s.p.span, T = s.p.carrier.tension;
    const double e = max_error(
        s, [&](double x)
        { return x < a ? P * x * (L - a) / (T * L) : P * (L - x) * a / (T * L); });
    EXPECT_LT(e, 1e-13) << to_string(method);
  }
}

TEST(StaticBeam, PointLoadConvergesToTheClosedForm)
{
  // Tensioned Euler-Bernoulli beam, point load at a vertex. Cubic Hermite
  // elements: nodal error O(h^4); finite differences: O(h^2). The boundary
  // layers have width sqrt(EI/T) = 0.1 m: grids from h = 0.1 m down resolve them.
  const double P = 100., a = 6.;
  for (const SpaceMethod method : {SpaceMethod::fem, SpaceMethod::fdm})
  {
    std::vector<double> errors;
    // FDM needs finer grids to reach its asymptotic regime (kh <= 0.25).
    const std::vector<unsigned int> grids =
        method == SpaceMethod::fem ? std::vector<unsigned int>{200, 400, 800}
                                   : std::vector<unsigned int>{400, 800, 1600};
    for (const unsigned int n : grids)
    {
      SingleWire s(method, n, Wire::contact_wire, 0., P, a);
      const auto& w = s.p.contact_wire;
      errors.push_back(max_error(s,
                                 [&](double x) {
                                   return beam_point_load(x, a, P, s.p.span, w.tension,
                                                          w.bending_stiffness);
                                 }));
    }
    const double expected_order = method == SpaceMethod::fem ? 4. : 2.;
    for (unsigned int i = 1; i < errors.size(); ++i)
      EXPECT_NEAR(std::log2(errors[i - 1] / errors[i]), expected_order, 0.15)
          << to_string(method) << " errors " << errors[i - 1] << ' ' << errors[i];
  }
}

TEST(StaticBeam, GravitySagMatchesTheClosedForm)
{
  // Uniform load rhoA g: closed form with cosh boundary layers of width
  // sqrt(EI/T) = 0.1 m. FEM at N+1 = 500 (h = 0.04): nodal error below 1e-9 m
  // on a sag of 3.5 cm; at mid-span round-off only (condition of K ~ 1e10).
  SingleWire s(SpaceMethod::fem, 500, Wire::contact_wire, 9.81, 0., 1.);
  const auto& w = s.p.contact_wire;
  const double q0 = w.mass_per_length * 9.81;
  EXPECT_NEAR(s.w(10.), beam_uniform_load(10., q0, 20., w.tension, w.bending_stiffness),
              1e-10);
  EXPECT_LT(max_error(s,
                      [&](double x) {
                        return beam_uniform_load(x, q0, 20., w.tension,
                                                 w.bending_stiffness);
                      }),
            1e-9);
}

namespace
{
StaticEquilibrium paper_static(SpaceMethod method, unsigned int n, double contact_force,
                               double x_p, SemiDiscreteSystem* keep = nullptr)
{
  const auto d = create_catenary_discretisation(CatenaryParameters(), grid(method, n));
  SemiDiscreteSystem system = build_catenary_system(*d, Constraint::Kind::unilateral);
  dealii::Vector<double> load(system.n_dofs());
  SparseRow F;
  d->load_row(x_p, 0, F);
  F.shift(system.block("contact wire").first);
  F.add_transpose_to(load, contact_force);
  StaticEquilibrium s = solve_static_equilibrium(system, load);
  if (keep)
    *keep = std::move(system);
  return s;
}
} // namespace

TEST(PaperStatic, DroppersHoldTheWireAndFemAndFdmAgree)
{
  // Fig. 5: both droppers taut (lambda > 0, gap = 0 to round-off). The dropper
  // forces of FEM and FDM differ only because FDM moves each dropper to its
  // control-volume node (5.5 -> 5.52 m): agreement within 1 %.
  const auto fem = paper_static(SpaceMethod::fem, 500, 8.75, 2.);
  const auto fdm = paper_static(SpaceMethod::fdm, 500, 8.75, 2.);
  for (unsigned int j = 0; j < 2; ++j)
  {
    EXPECT_TRUE(fem.active[j]);
    EXPECT_GT(fem.multipliers[j], 50.);
    EXPECT_LT(std::abs(fem.gaps[j]), 1e-12);
    EXPECT_LT(std::abs(fdm.gaps[j]), 1e-12);
    EXPECT_NEAR(fdm.multipliers[j] / fem.multipliers[j], 1., 0.01) << "dropper " << j + 1;
  }
}

TEST(PaperStatic, FemDropperForcesConvergeFastOnlyWhenDroppersSitOnVertices)
{
  // With the droppers on vertices (N+1 = 1000, 2000: h = 0.02, 0.01 m) the
  // dropper forces agree to 1e-7. At N+1 = 500 the droppers sit at cell
  // midpoints: the kink of the carrier under a dropper falls inside a linear
  // element, and the force is off by O(h) (here 1e-3 relative): the "too
  // smooth ansatz" of Sec. 4.2. doc/formulation.md discusses it.
  const auto midpoints = paper_static(SpaceMethod::fem, 500, 8.75, 2.);
  const auto fine = paper_static(SpaceMethod::fem, 1000, 8.75, 2.);
  const auto finer = paper_static(SpaceMethod::fem, 2000, 8.75, 2.);
  for (unsigned int j = 0; j < 2; ++j)
  {
    EXPECT_NEAR(fine.multipliers[j] / finer.multipliers[j], 1., 1e-7);
    EXPECT_NEAR(midpoints.multipliers[j] / finer.multipliers[j], 1., 2e-3);
    EXPECT_GT(std::abs(midpoints.multipliers[j] / finer.multipliers[j] - 1.), 1e-4);
  }
}

TEST(PaperStatic, DropperSlackensUnderALargeUpliftAndComplementarityHolds)
{
  // A 300 N uplift below dropper 1 (which carries 84 N at rest) pushes the
  // wire up: dropper 1 goes slack (lambda = 0, gap > 0) while dropper 2 stays
  // taut: conditions (5), (6).
  const auto s = paper_static(SpaceMethod::fem, 200, 300., 5.5);
  EXPECT_FALSE(s.active[0]);
  EXPECT_EQ(s.multipliers[0], 0.);
  EXPECT_GT(s.gaps[0], 1e-3);
  EXPECT_TRUE(s.active[1]);
  EXPECT_GT(s.multipliers[1], 0.);
  EXPECT_LT(std::abs(s.gaps[1]), 1e-12);
  EXPECT_GE(s.active_set_iterations, 2u);
}

TEST(PaperStatic, TheSaddlePointSystemGivesTheSameEquilibrium)
{
  // StaticEquilibriumSolver forms the dense Schur complement G K^-1 G^T for
  // few constraints and factorises the saddle-point system [K G^T; G -C] by
  // UMFPACK for many (long sections, doc/benchmarks.md "Setup against the
  // number of spans"); a column budget of 0 forces the second way. Both solve
  // the same equations: the same active set after the same iterations (here
  // with a change, the 300 N uplift below dropper 1), and q and lambda equal
  // to round-off: 1e-10 of their largest magnitude (the condition of these
  // systems is about 1e6, so eps times it is 2e-10; UMFPACK's pivoting of
  // the indefinite system differs from the Schur complement's Cholesky by
  // up to 1.0e-12 relative, measured).
  const auto d =
      create_catenary_discretisation(CatenaryParameters(), grid(SpaceMethod::fem, 200));
  const SemiDiscreteSystem system =
      build_catenary_system(*d, Constraint::Kind::unilateral);
  dealii::Vector<double> load(system.n_dofs());
  SparseRow F;
  d->load_row(5.5, 0, F);
  F.shift(system.block("contact wire").first);
  F.add_transpose_to(load, 300.);
  const StaticEquilibriumSolver dense(system), sparse(system, 0., 0.);
  EXPECT_FALSE(dense.uses_saddle_point_system());
  EXPECT_TRUE(sparse.uses_saddle_point_system());
  const StaticEquilibrium a = dense.solve(load), b = sparse.solve(load);
  ASSERT_EQ(a.q.size(), b.q.size());
  EXPECT_GE(b.active_set_iterations, 2u);
  EXPECT_EQ(a.active_set_iterations, b.active_set_iterations);
  EXPECT_EQ(a.active, b.active);
  const double q_scale = a.q.linfty_norm();
  for (unsigned int i = 0; i < a.q.size(); ++i)
    ASSERT_NEAR(a.q(i), b.q(i), 1e-10 * q_scale) << "unknown " << i;
  double lambda_scale = 0.;
  for (const double l : a.multipliers)
    lambda_scale = std::max(lambda_scale, std::abs(l));
  for (unsigned int i = 0; i < a.multipliers.size(); ++i)
    EXPECT_NEAR(a.multipliers[i], b.multipliers[i], 1e-10 * lambda_scale) << i;
}

TEST(PaperStatic, GridTooCoarseForTheDroppersIsAnInputError)
{
  // N+1 = 2 (nodes at 0, 10, 20 m): both FDM droppers fall on node 1.
  const auto d =
      create_catenary_discretisation(CatenaryParameters(), grid(SpaceMethod::fdm, 2));
  try
  {
    build_catenary_system(*d, Constraint::Kind::unilateral);
    FAIL() << "expected an InputError";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("Number of intervals = 2"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("same node"), std::string::npos);
  }
}
