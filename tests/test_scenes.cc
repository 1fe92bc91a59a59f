// Scenes (issue 7): the shipped prm/scenes/*.prm files run as they are and
// meet their known answers (series solution of the moving load, conserved
// energy and the period of free vibration, the closed-form response of a
// pantograph on a rigid wire, the grid-crossing oscillations of a point load),
// and effects a scene leaves out are not assembled.
#include <pantocat/analysis/moving_load_series.h>
#include <pantocat/app/parameter_input.h>
#include <pantocat/app/program_parameters.h>
#include <pantocat/app/run_modes.h>
#include <pantocat/base/input_error.h>
#include <pantocat/scene/scene_builder.h>
#include <pantocat/simulation/case_runner.h>
#include <pantocat/simulation/moving_load_comparison.h>

#include <deal.II/lac/full_matrix.h>

#include <gtest/gtest.h>

#include "support/rigid_wire_response.h"
#include <algorithm>

#include <cmath>
#include <complex>

using namespace pantocat;

namespace
{
ProgramParameters shipped_scene(const std::string& name,
                                const std::vector<std::string>& overrides = {})
{
  dealii::ParameterHandler prm;
  ProgramParameters::declare_parameters(prm);
  read_parameter_file(prm, std::string(PANTOCAT_SOURCE_DIR) + "/prm/scenes/" + name,
                      overrides);
  ProgramParameters p;
  p.parse_parameters(prm);
  return p;
}

/// Every reported time point of a run.
struct Recorder : SimulationObserver
{
  void observe(const TimePoint& p) override { points.push_back(p); }
  std::vector<TimePoint> points;
};

std::vector<TimePoint> run(const ProgramParameters& p)
{
  CaseRunner simulation(p.make_case(), {p.output.probe_positions, p.output.energy});
  Recorder recorder;
  simulation.run({&recorder});
  return recorder.points;
}

/// max_t |w(x_j, t) - w_series(x_j, t)| / max_t |w_series| at probe j.
double relative_series_error(const ProgramParameters& p, const unsigned int j)
{
  const MovingLoadSeries series = moving_load_series(p.make_case());
  double error = 0., reference = 0.;
  for (const TimePoint& point : run(p))
  {
    const double w = series.displacement(p.output.probe_positions[j], point.t);
    error = std::max(error, std::abs(point.probes[j] - w));
    reference = std::max(reference, std::abs(w));
  }
  return error / reference;
}
} // namespace

TEST(Scene, DefaultSceneIsThePapersBenchmarkWithNothingLeftOut)
{
  const ProgramParameters p = shipped_scene("benchmark.prm");
  const auto space = create_catenary_discretisation(p.catenary, p.discretisation);
  const BuiltScene s = build_scene(p.scene, p.catenary, *space);
  // Sec. 6, N+1 = 500 FDM: 499 + 499 wire unknowns, 2 pantograph bodies; 2 droppers
  // and the contact. Left out: what one span with viscous damping does not have
  // (stitch wires, steady arms and carrier supports sit at supports between
  // spans; Rayleigh damping is the alternative to the paper's beta) and the
  // moving force (an alternative pantograph).
  EXPECT_EQ(s.system.n_dofs(), 1000u);
  EXPECT_EQ(s.system.n_constraints(), 3u);
  EXPECT_EQ(s.active_effects.size(), 10u);
  EXPECT_EQ(s.inactive_effects,
            (std::vector<std::string>{"stitch wires", "steady arms", "carrier supports",
                                      "Rayleigh damping", "moving force"}));
}

TEST(Scene, LeftOutEffectsAreNotAssembled)
{
  ProgramParameters p = shipped_scene("benchmark.prm");
  p.scene.carrier = WireModel::rigid;
  p.scene.damping = false;
  p.scene.contact_wire_bending = false;
  const auto space = create_catenary_discretisation(p.catenary, p.discretisation);
  const BuiltScene s = build_scene(p.scene, p.catenary, *space);
  // No carrier unknowns, a zero damping matrix in the wire (the pantograph keeps its
  // own dampers), a tridiagonal wire block (no bending stencil).
  EXPECT_FALSE(s.system.has_block("carrier"));
  EXPECT_EQ(s.system.n_dofs(), 501u);
  const DofBlock& wire = s.system.block("contact wire");
  double wire_damping = 0.;
  for (unsigned int i = wire.first; i < wire.first + wire.size; ++i)
    wire_damping += std::abs(s.system.damping.el(i, i));
  EXPECT_EQ(wire_damping, 0.);
  EXPECT_EQ(s.system.sparsity->row_length(wire.first + 10), 3u);
}

TEST(Scene, MovingForceOnAStringMatchesTheSeriesSolution)
{
  // FDM, N+1 = 400 (8 cells per load width 2 eps), half-explicit, v = 60 m/s
  // (wave speed 118.5 m/s). Measured: 0.64 % at midspan, 0.32 % on N+1 = 800.
  const ProgramParameters p = shipped_scene("moving-force-string.prm");
  const double e400 = relative_series_error(p, 1);
  EXPECT_LT(e400, 0.01);
  ProgramParameters fine = p;
  fine.discretisation.n_intervals = 800;
  const double e800 = relative_series_error(fine, 1);
  // Halving h at least halves the error (order 2 asymptotically; 1.0 measured
  // here, where the grid resolves delta_eps with 8 and 16 cells).
  EXPECT_GT(e400 / e800, 1.8);
}

TEST(Scene, MovingForceOnABeamMatchesTheSeriesSolution)
{
  // FEM (C1 Hermite), N+1 = 100, BDF-2, dt = 2e-5 s. Measured 0.047 % at midspan;
  // N+1 = 50 gives 0.19 % (ratio 4.1: the space error dominates).
  const ProgramParameters p = shipped_scene("moving-force-beam.prm");
  const double e100 = relative_series_error(p, 1);
  EXPECT_LT(e100, 1e-3);
  ProgramParameters coarse = p;
  coarse.discretisation.n_intervals = 50;
  EXPECT_GT(relative_series_error(coarse, 1) / e100, 3.5);
}

TEST(Scene, UndampedFreeVibrationConservesEnergyAndHasTheModalPeriod)
{
  const ProgramParameters p = shipped_scene("free-vibration-beam.prm");
  const auto points = run(p);
  // The reversible half-explicit method: the energy oscillates with
  // O((omega_1 dt)^2) = 1e-6 and does not drift (20000 steps; measured 2.2e-7).
  const double e0 = points.front().energy;
  double variation = 0.;
  for (const TimePoint& point : points)
    variation = std::max(variation, std::abs(point.energy - e0) / e0);
  EXPECT_LT(variation, 1e-6);
  EXPECT_LT(std::abs(points.back().energy - e0) / e0, 1e-6);

  // Period from the upward zero crossings of w(10 m) (linear interpolation).
  std::vector<double> crossings;
  for (std::size_t i = 1; i < points.size(); ++i)
  {
    const double a = points[i - 1].probes[0], b = points[i].probes[0];
    if (a < 0. && b >= 0.)
      crossings.push_back(points[i - 1].t +
                          (points[i].t - points[i - 1].t) * a / (a - b));
  }
  ASSERT_GE(crossings.size(), 3u);
  const double period = (crossings.back() - crossings.front()) / (crossings.size() - 1);
  const WireParameters& w = p.catenary.contact_wire;
  const double k = M_PI / p.catenary.span;
  const double omega = std::sqrt(
      (w.tension * k * k + w.bending_stiffness * std::pow(k, 4)) / w.mass_per_length);
  // The FDM string operator has omega_h = omega (1 - (k h)^2 / 24 + ...) (bending adds
  // 2.5e-4 of that at k = pi/L); the time error (omega dt)^2 / 24 = 4e-8.
  // Measured period ratio - 1 = 4.11e-5.
  const double kh = k * p.catenary.span / p.discretisation.n_intervals;
  EXPECT_NEAR(period * omega / (2. * M_PI) - 1., kh * kh / 24., 2e-6);
}

TEST(Scene, PantographOnARigidWireFollowsTheClosedForm)
{
  const ProgramParameters p = shipped_scene("pantograph-rigid-wire.prm");
  const auto points = run(p);
  // Head fixed at the wire: the damped frame oscillator in closed form.
  double error = 0.;
  for (const TimePoint& point : points)
  {
    error = std::max(error, std::abs(point.lambda.back() -
                                     rigid_wire_contact_force(p.pantograph(), point.t)));
    EXPECT_LT(std::abs(point.pantograph[0]), 1e-12); // the head stays on the wire
  }
  // dt = 1e-4 s, omega = 20.3 1/s: an O((omega dt)^2) = 4e-6 relative error of the
  // 35 N swing, 1.4e-4 N; measured 1.6e-5 N.
  EXPECT_LT(error, 2e-4);
}

TEST(Scene, ThreeMassPantographAtRestOnARigidWireStaysAtRest)
{
  // In its static state (offset -F_0/c_1, lambda_p(0) = F_0) the three-mass model
  // on a rigid wire carries lambda_p = F_0 at all times.
  const ProgramParameters p =
      shipped_scene("pantograph-rigid-wire.prm",
                    {"Scene/Pantograph=three-mass", "Pantograph/Initial contact force=70",
                     "Pantograph/Initial offset=-0.01"});
  for (const TimePoint& point : run(p))
    ASSERT_NEAR(point.lambda.back(), 70., 1e-9) << "t = " << point.t;
}

TEST(Scene, PointLoadOscillatesAtTheGridCrossingFrequency)
{
  // FEM N+1 = 125 (h = 0.16 m) at 32 m/s: x_p crosses a grid point every
  // h / v = 5 ms. With the point load (15)/(16), d^2 F_w/dt^2 jumps at each
  // crossing (the Hermite functions' second derivatives jump at the nodes).
  const ProgramParameters point = shipped_scene("point-load.prm");
  const ProgramParameters smooth =
      shipped_scene("point-load.prm", {"Discretisation/Load shape=smoothed delta"});
  const auto a = run(point), b = run(smooth);
  const auto second_difference = [](const std::vector<TimePoint>& s)
  {
    double d = 0.;
    for (std::size_t i = 1; i + 1 < s.size(); ++i)
      d = std::max(d, std::abs(s[i + 1].lambda.back() - 2. * s[i].lambda.back() +
                               s[i - 1].lambda.back()));
    return d;
  };
  // Measured 1.19 N against 0.053 N.
  EXPECT_GT(second_difference(a), 10. * second_difference(b));

  // Fourier amplitude of lambda_p at the crossing frequency v/h and its first
  // two harmonics: measured 1.28 + 0.87 + 0.23 N (point) against 0.25 + 0.08 + 0.04 N.
  const auto amplitude = [](const std::vector<TimePoint>& s, const double f)
  {
    double mean = 0.;
    for (const auto& p : s)
      mean += p.lambda.back() / s.size();
    std::complex<double> sum = 0.;
    for (const auto& p : s)
      sum += (p.lambda.back() - mean) * std::polar(1., -2. * M_PI * f * p.t);
    return 2. * std::abs(sum) / s.size();
  };
  const double f =
      point.pantograph().speed * point.discretisation.n_intervals / point.catenary.span;
  double spurious_point = 0., spurious_smooth = 0.;
  for (const double harmonic : {1., 2., 3.})
  {
    spurious_point += amplitude(a, harmonic * f);
    spurious_smooth += amplitude(b, harmonic * f);
  }
  EXPECT_GT(spurious_point, 4. * spurious_smooth);
}

TEST(Scene, InconsistentScenesAreRefused)
{
  const auto refused = [](const std::vector<std::string>& overrides)
  {
    try
    {
      shipped_scene("benchmark.prm", overrides);
    }
    catch (const InputError& e)
    {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(refused({"Scene/Contact wire=rigid", "Scene/Pantograph=moving force"})
                .find("Scene/Pantograph = moving force"),
            std::string::npos);
  EXPECT_NE(refused({"Scene/Initial state=rest"}).find("Scene/Initial state = rest"),
            std::string::npos);
  EXPECT_NE(
      refused({"Scene/Contact wire tension=false", "Scene/Contact wire bending=false"})
          .find("Scene/Contact wire tension = false"),
      std::string::npos);
}

TEST(Scene, ACarrierWithBendingIsAssembledAsTheContactWire)
{
  // Given the contact wire's data, a carrier with bending (C1 Hermite for FEM, the
  // five-point stencil for FDM) must give the contact wire's M, D, K and loads
  // (the clamp loads act on both wires alike): to the last bit.
  for (const std::string method : {"fem", "fdm"})
  {
    ProgramParameters p = shipped_scene(
        "benchmark.prm",
        {"Scene/Pantograph=absent", "Scene/Messenger bending=true",
         "Discretisation/Messenger element=cubic Hermite",
         "Discretisation/Method=" + method, "Discretisation/Number of intervals=50",
         "Catenary/Messenger/Bending stiffness=1"});
    p.catenary.carrier = p.catenary.contact_wire;
    const auto space = create_catenary_discretisation(p.catenary, p.discretisation);
    const BuiltScene s = build_scene(p.scene, p.catenary, *space);
    const DofBlock &c = s.system.block("carrier"), &w = s.system.block("contact wire");
    ASSERT_EQ(c.size, w.size) << method;
    for (unsigned int i = 0; i < c.size; ++i)
    {
      EXPECT_EQ(s.system.load(c.first + i), s.system.load(w.first + i)) << method;
      for (unsigned int j = 0; j < c.size; ++j)
        for (const auto* m : {&s.system.mass, &s.system.damping, &s.system.stiffness})
          ASSERT_EQ(m->el(c.first + i, c.first + j), m->el(w.first + i, w.first + j))
              << method << " (" << i << ", " << j << ")";
    }
  }
}

TEST(Scene, CarrierBendingNeedsAnElementWithSecondDerivatives)
{
  try
  {
    shipped_scene("benchmark.prm", {"Scene/Messenger bending=true",
                                    "Catenary/Messenger/Bending stiffness=1",
                                    "Discretisation/Method=fem"});
    FAIL() << "linear Lagrange carrier with bending accepted";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(
        std::string(e.what()).find("Discretisation/Messenger element = linear Lagrange"),
        std::string::npos)
        << e.what();
  }
}

TEST(Scene, EveryIntegratorEvaluatesTheTimeDependentLoad)
{
  // f(t) of the moving force: half-explicit at t_n, BDF-2 and generalized-alpha at
  // t_{n+1}, IDA in its residual (a scene without constraints: no roots). All four
  // match the series within the space error of N+1 = 100 (0.032-0.035 % measured
  // to x_p = 10 m).
  for (const std::string integrator :
       {"half-explicit", "bdf2", "generalized-alpha", "ida"})
  {
    const ProgramParameters p = shipped_scene(
        "moving-force-beam.prm",
        {"Time integration/Integrator=" + integrator, "Pantograph/Final position=10"});
    EXPECT_LT(relative_series_error(p, 1), 1e-3) << integrator;
  }
}

namespace
{
/// e^{A t} of a small matrix: scaling and squaring of the Taylor series (to round-off).
dealii::FullMatrix<double> exponential(const dealii::FullMatrix<double>& A,
                                       const double t)
{
  const unsigned int n = A.m();
  unsigned int squarings = 0;
  double norm = A.linfty_norm() * t;
  while (norm > 0.5)
    norm /= 2., ++squarings;
  dealii::FullMatrix<double> X(A), E(n, n), term(n, n), next(n, n);
  for (unsigned int i = 0; i < n; ++i)
    E(i, i) = term(i, i) = 1.;
  X *= t / std::pow(2., squarings);
  for (unsigned int k = 1; k <= 20; ++k)
  {
    term.mmult(next, X);
    next /= k;
    term = next;
    E.add(1., term);
  }
  for (unsigned int s = 0; s < squarings; ++s)
  {
    E.mmult(next, E);
    E = next;
  }
  return E;
}
} // namespace

TEST(Scene, ThreeMassPantographOnARigidWireFollowsTheExactTwoBodyResponse)
{
  // Head held at the wire (bilateral): bodies 2 and 3 form a damped 2-DOF system
  // x' = A x + b, x = (w_2, w_3, w_2', w_3'), solved exactly with e^{A t}; the
  // contact force is lambda_p = c_1 w_2 + d_1 w_2'. Body 2 starts 5 mm below its
  // static place with the consistent lambda_p(0).
  const double offset = -0.005;
  ProgramParameters p =
      shipped_scene("pantograph-rigid-wire.prm",
                    {"Scene/Pantograph=three-mass",
                     "Pantograph/Initial offset=" + std::to_string(offset)});
  const auto& m = p.pantograph().three_mass;
  p.pantograph().initial_contact_force = -m.stiffnesses[0] * offset; // then w_2'(0) = 0
  const auto points = run(p);

  const double m2 = m.masses[1], m3 = m.masses[2];
  const double c1 = m.stiffnesses[0], c2 = m.stiffnesses[1], c3 = m.stiffnesses[2];
  const double d1 = m.dampings[0], d2 = m.dampings[1], d3 = m.dampings[2];
  dealii::FullMatrix<double> A(4, 4);
  A(0, 2) = A(1, 3) = 1.;
  A(2, 0) = -(c1 + c2) / m2, A(2, 1) = c2 / m2, A(2, 2) = -(d1 + d2) / m2,
       A(2, 3) = d2 / m2;
  A(3, 0) = c2 / m3, A(3, 1) = -(c2 + c3) / m3, A(3, 2) = d2 / m3,
       A(3, 3) = -(d2 + d3) / m3;
  dealii::Vector<double> b(4), x0(4);
  b(3) = m.uplift_force / m3;
  // The model's start (ThreeMassPantograph::consistent_state): w_2 = -offset,
  // w_3 = (F_0 + c_2 w_2) / (c_2 + c_3), both at rest.
  x0(0) = -offset;
  x0(1) = (m.uplift_force + c2 * x0(0)) / (c2 + c3);
  double error = 0., swing = 0.;
  for (const TimePoint& point : points)
  {
    // x(t) = e^{At} x0 + int_0^t e^{As} ds b, the integral from the augmented matrix.
    dealii::FullMatrix<double> Ab(5, 5);
    for (unsigned int i = 0; i < 4; ++i)
    {
      for (unsigned int j = 0; j < 4; ++j)
        Ab(i, j) = A(i, j);
      Ab(i, 4) = b(i);
    }
    const dealii::FullMatrix<double> E = exponential(Ab, point.t);
    double w2 = 0., v2 = 0.;
    for (unsigned int j = 0; j < 4; ++j)
      w2 += E(0, j) * x0(j), v2 += E(2, j) * x0(j);
    w2 += E(0, 4), v2 += E(2, 4);
    const double lambda = c1 * w2 + d1 * v2;
    error = std::max(error, std::abs(point.lambda.back() - lambda));
    swing = std::max(swing, std::abs(lambda - m.uplift_force));
  }
  EXPECT_GT(swing, 20.); // a real transient (35 N), not the static state
  // Second order at dt = 1e-4 s: at most (omega dt)^2 x swing = 2e-3 N for the
  // fastest mode (omega ~ 80 1/s); a first-order method would be off by ~0.3 N.
  // Measured 5.1e-5 N.
  EXPECT_LT(error, 1e-3);
}
