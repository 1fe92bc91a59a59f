// The mass-chain pantograph (MassChainPantograph, doc/pantographs.md): its
// eigenfrequencies in closed form, the paper's two-mass model and the
// three-mass model as chains, the steady contact force F_0 + a + b v^2 on a
// rigid wire, the S55 pantograph at rest in its reference state, and
// pantographs spaced along the line (Scene/Pantograph spacing).
#include <pantocat/app/parameter_input.h>
#include <pantocat/app/program_parameters.h>
#include <pantocat/base/input_error.h>
#include <pantocat/pantograph/mass_chain_pantograph.h>
#include <pantocat/pantograph/three_mass_pantograph.h>
#include <pantocat/pantograph/two_mass_pantograph.h>
#include <pantocat/simulation/case_runner.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include "support/case_files.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

using namespace pantocat;

namespace
{
struct Recorder : SimulationObserver
{
  void observe(const TimePoint& p) override { points.push_back(p); }
  std::vector<TimePoint> points;
};

std::vector<TimePoint> run(const ProgramParameters& p)
{
  CaseRunner runner(p.make_case());
  Recorder recorder;
  runner.run({&recorder});
  return recorder.points;
}

/// omega^2 of the free chain (no contact): det(K - omega^2 M) = 0 from the
/// assembled M and K of the body, by LAPACK on M^-1/2 K M^-1/2 (M is diagonal).
std::vector<double> squared_eigenfrequencies(const PantographModel& model)
{
  BlockOperator op;
  model.assemble(op);
  const unsigned int n = op.size();
  dealii::LAPACKFullMatrix<double> A(n, n);
  for (unsigned int i = 0; i < n; ++i)
    for (unsigned int j = 0; j < n; ++j)
      A(i, j) = op.stiffness.el(i, j) /
                std::sqrt(op.mass.diag_element(i) * op.mass.diag_element(j));
  dealii::Vector<double> values;
  dealii::FullMatrix<double> vectors;
  A.compute_eigenvalues_symmetric(-1., 1e300, 0., values, vectors);
  std::vector<double> w(values.begin(), values.end());
  std::sort(w.begin(), w.end());
  return w;
}

/// Every entry of the three matrices and the load, compared to the bit.
void expect_same_operators(const PantographModel& a, const PantographModel& b)
{
  BlockOperator x, y;
  a.assemble(x);
  b.assemble(y);
  ASSERT_EQ(x.size(), y.size());
  for (unsigned int i = 0; i < x.size(); ++i)
  {
    EXPECT_EQ(x.load(i), y.load(i)) << i;
    for (unsigned int j = 0; j < x.size(); ++j)
    {
      EXPECT_EQ(x.mass.el(i, j), y.mass.el(i, j)) << i << ", " << j;
      EXPECT_EQ(x.damping.el(i, j), y.damping.el(i, j)) << i << ", " << j;
      EXPECT_EQ(x.stiffness.el(i, j), y.stiffness.el(i, j)) << i << ", " << j;
    }
  }
}

/// A prm file in the working directory that includes @p files (absolute).
std::string including(const std::string& name, const std::vector<std::string>& files)
{
  std::ofstream out(name);
  for (const std::string& f : files)
    out << "include " << f << "\n";
  return name;
}
} // namespace

TEST(MassChain, OneBodyOscillatesAtSqrtKOverM)
{
  // n = 1: m w'' + k w = 0, omega = sqrt(k / m). 1e-12 relative: a 1x1
  // eigenproblem, round-off only.
  MassChainPantographParameters p;
  p.masses = {6.0};
  p.stiffnesses = {160.};
  p.dampings = {100.};
  const auto w2 = squared_eigenfrequencies(MassChainPantograph(p, 0.));
  ASSERT_EQ(w2.size(), 1u);
  EXPECT_NEAR(std::sqrt(w2[0]), std::sqrt(160. / 6.), 1e-12 * std::sqrt(160. / 6.));
}

TEST(MassChain, TwoBodiesOscillateAtTheRootsOfTheCharacteristicPolynomial)
{
  // n = 2: det(K - w M) = m_1 m_2 w^2 - (m_1 (k_1 + k_2) + m_2 k_1) w + k_1 k_2,
  // w = omega^2; its roots by the stable quadratic formula. 1e-12 relative:
  // LAPACK on a 2x2 matrix, round-off of a few ulp.
  MassChainPantographParameters p;
  p.masses = {9.0, 17.0};
  p.stiffnesses = {7000., 500.};
  p.dampings = {30., 130.};
  const double m1 = 9., m2 = 17., k1 = 7000., k2 = 500.;
  const double a = m1 * m2, b = -(m1 * (k1 + k2) + m2 * k1), c = k1 * k2;
  const double big = (-b + std::sqrt(b * b - 4. * a * c)) / (2. * a);
  const double small = c / (a * big);
  const auto w2 = squared_eigenfrequencies(MassChainPantograph(p, 0.));
  ASSERT_EQ(w2.size(), 2u);
  EXPECT_NEAR(std::sqrt(w2[0]), std::sqrt(small), 1e-12 * std::sqrt(small));
  EXPECT_NEAR(std::sqrt(w2[1]), std::sqrt(big), 1e-12 * std::sqrt(big));
  // The roots: 4.3663 and 34.6394 rad/s (0.695 and 5.513 Hz).
  EXPECT_NEAR(std::sqrt(small), 4.3663, 1e-4);
  EXPECT_NEAR(std::sqrt(big), 34.6394, 1e-4);
}

TEST(MassChain, TwoAndThreeMassModelsAreChainsToTheBit)
{
  // The exact mapping: two-mass (m_1, m_2; c_1, c_2; d_1, d_2; F_0 on body 2)
  // is the chain with Masses = m_1, m_2, Stiffnesses = c_1, c_2, Dampings =
  // d_1, d_2, Static force = F_0, Force body = 2 (the frame), no aerodynamic
  // force, Reference state = relaxed springs; three-mass likewise with three
  // values. Same M, D, K and f to the bit, and with Initial configuration =
  // offset the same consistent state (13).
  const TwoMassPantographParameters two;
  MassChainPantographParameters chain2; // the defaults are the two-mass data
  chain2.start = ChainStart::offset;
  expect_same_operators(TwoMassPantograph(two), MassChainPantograph(chain2, 32.));

  const ThreeMassPantographParameters three;
  MassChainPantographParameters chain3;
  chain3.masses.assign(three.masses.begin(), three.masses.end());
  chain3.stiffnesses.assign(three.stiffnesses.begin(), three.stiffnesses.end());
  chain3.dampings.assign(three.dampings.begin(), three.dampings.end());
  chain3.static_force = three.uplift_force;
  chain3.start = ChainStart::offset;
  expect_same_operators(ThreeMassPantograph(three), MassChainPantograph(chain3, 32.));

  dealii::Vector<double> q1, v1, q2, v2;
  ThreeMassPantograph(three).consistent_state(-0.03, 0.2, 1.5, 8.75, 0.002, q1, v1);
  MassChainPantograph(chain3, 32.).consistent_state(-0.03, 0.2, 1.5, 8.75, 0.002, q2, v2);
  for (unsigned int i = 0; i < 3; ++i)
  {
    EXPECT_EQ(q1(i), q2(i)) << i;
    EXPECT_EQ(v1(i), v2(i)) << i;
  }
}

TEST(MassChain, TwoMassChainReproducesTheTwoMassBenchmarkToTheBit)
{
  // prm/benchmark-32.prm shortened to x_p = 2..6 m: the two-mass model, and
  // the mass chain with its defaults (the two-mass data) and the paper's start
  // (13). Same operators and state (test above) and the same operations, so
  // every contact force agrees to the bit.
  const std::vector<std::string> shorter{"Pantograph/Final position=6"};
  auto chain = shorter;
  chain.insert(chain.end(), {"Scene/Pantograph=mass-chain",
                             "Pantograph/Mass-chain model/Initial configuration=offset"});
  const auto a = run(read_case(source_file("prm/benchmark-32.prm"), shorter));
  const auto b = run(read_case(source_file("prm/benchmark-32.prm"), chain));
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GT(a.size(), 100u);
  for (std::size_t n = 0; n < a.size(); ++n)
  {
    ASSERT_EQ(a[n].lambda.back(), b[n].lambda.back()) << "t = " << a[n].t;
    ASSERT_EQ(a[n].pantograph, b[n].pantograph) << "t = " << a[n].t;
  }
}

TEST(MassChain, SteadyContactForceOnARigidWireIsStaticPlusAerodynamicForce)
{
  // prm/scenes/pantograph-rigid-wire.prm with a chain whose frame has no
  // ground spring (k_2 = 0): with the head held at 0 the steady frame position
  // carries lambda_p = F_0 + a + b v^2 whatever it is. m = (1, 1) kg,
  // k_1 = 1e5 N/m, c_1 + c_2 = 632 N s/m = 2 sqrt(k_1 m_2) (critical): the
  // transient from lambda_p(0) = 35 N decays as t e^{-316 t}, below 1e-12 N after
  // 0.1 s. Asserted 1e-6 relative over t > 0.1 s: what is left is the
  // integrator's round-off in the steady state.
  for (const double speed : {32., 64.})
  {
    const double a = 10., b = 0.02;
    const ProgramParameters p = read_case(
        source_file("prm/scenes/pantograph-rigid-wire.prm"),
        {"Scene/Pantograph=mass-chain", "Pantograph/Speed=" + std::to_string(speed),
         "Pantograph/Mass-chain model/Masses=1, 1",
         "Pantograph/Mass-chain model/Stiffnesses=1e5, 0",
         "Pantograph/Mass-chain model/Dampings=316, 316",
         "Pantograph/Mass-chain model/Aerodynamic force a=10",
         "Pantograph/Mass-chain model/Aerodynamic force b=0.02"});
    const double expected = 70. + a + b * speed * speed; // 100.48 N and 161.92 N
    unsigned int steady = 0;
    for (const TimePoint& point : run(p))
      if (point.t > 0.1)
      {
        ++steady;
        ASSERT_NEAR(point.lambda.back(), expected, 1e-6 * expected)
            << "v = " << speed << ", t = " << point.t;
      }
    EXPECT_GT(steady, 100u) << speed;
  }
}

TEST(MassChain, S55PantographInItsReferenceStateRestsAtZeroWithF0)
{
  // prm/pantographs/s55-three-mass.prm on a rigid wire at z = 0, started in
  // static equilibrium: q = 0 with lambda_p(0) = F_0 = 169 N, the load is
  // F_0 on the head, and nothing moves. To round-off: 1e-11 N (the static
  // saddle-point solve of the whole system) and 1e-15 m.
  const std::string file = including("mass_chain_s55.prm",
                                     {source_file("prm/scenes/pantograph-rigid-wire.prm"),
                                      source_file("prm/pantographs/s55-three-mass.prm")});
  const ProgramParameters p =
      read_case(file, {"Pantograph/Final position=6", "Run/Start=static equilibrium"});
  const MassChainPantographParameters& s55 = p.scene.pantographs[0].parameters.mass_chain;
  ASSERT_EQ(s55.n_bodies(), 3u);
  EXPECT_EQ(s55.uplift_body(), 3u);
  EXPECT_EQ(s55.reference, ChainReference::static_equilibrium);
  // The load of (10) in the reference state: F_0 on the head, nothing on the frame.
  const MassChainPantograph model(s55, p.scene.pantographs[0].parameters.speed);
  const dealii::Vector<double> f = model.constant_load();
  EXPECT_EQ(f(0), 169.);
  EXPECT_EQ(f(1), 0.);
  EXPECT_EQ(f(2), 0.);
  EXPECT_EQ(model.static_force(), 169.);
  const auto points = run(p);
  ASSERT_GT(points.size(), 100u);
  for (const TimePoint& point : points)
  {
    ASSERT_NEAR(point.lambda.back(), 169., 1e-11) << "t = " << point.t;
    ASSERT_EQ(point.pantograph.size(), 3u);
    for (const double q : point.pantograph)
      ASSERT_LE(std::abs(q), 1e-15) << "t = " << point.t;
  }
}

TEST(MassChain, S55ReferenceStateIsTheRelaxedChainShiftedByItsStaticState)
{
  // The static states K q = f - lambda e_1 of the S55 chain for lambda = 100,
  // 169 and 250 N. In the reference state (f = F_0 e_1): lambda = F_0 - k_3 q_3,
  // the data sheet's quasi-static force F_0 - k_1 z_1 (its k_1 is our k_3 =
  // 160 N/m), and lambda = F_0 gives q = 0. With relaxed springs (f = F_0 e_3)
  // the static states are those of the reference state shifted by one constant
  // x* with K x* = F_0 (e_3 - e_1). Round-off of a 3x3 solve: 1e-9 N, 1e-12 m.
  const std::string file = including("mass_chain_s55_static.prm",
                                     {source_file("prm/scenes/pantograph-rigid-wire.prm"),
                                      source_file("prm/pantographs/s55-three-mass.prm")});
  const ProgramParameters p = read_case(file);
  MassChainPantographParameters reference = p.scene.pantographs[0].parameters.mass_chain;
  MassChainPantographParameters relaxed = reference;
  relaxed.reference = ChainReference::relaxed_springs;
  const auto static_state =
      [](const MassChainPantographParameters& data, const double lambda)
  {
    BlockOperator op;
    MassChainPantograph(data, 0.).assemble(op);
    dealii::FullMatrix<double> K(3, 3);
    K.copy_from(op.stiffness);
    K.gauss_jordan();
    dealii::Vector<double> rhs = op.load, q(3);
    rhs(0) -= lambda;
    K.vmult(q, rhs);
    return q;
  };
  dealii::Vector<double> shift;
  for (const double lambda : {100., 169., 250.})
  {
    const dealii::Vector<double> q = static_state(reference, lambda);
    EXPECT_NEAR(lambda, 169. - 160. * q(2), 1e-9) << lambda;
    dealii::Vector<double> x = static_state(relaxed, lambda);
    x -= q;
    if (shift.size() == 0)
      shift = x;
    for (unsigned int i = 0; i < 3; ++i)
      EXPECT_NEAR(x(i), shift(i), 1e-12) << lambda << ", " << i;
    if (lambda == 169.)
    {
      EXPECT_LT(q.linfty_norm(), 1e-15);
    }
  }
  // K x* = F_0 (e_3 - e_1) in closed form: the ground spring carries nothing
  // (x*_3 = 0), links 1 and 2 are compressed by F_0: x*_2 = -F_0 / k_2,
  // x*_1 = x*_2 - F_0 / k_1 (k_1 = 7000, k_2 = 15500 N/m, head first).
  EXPECT_NEAR(shift(2), 0., 1e-12);
  EXPECT_NEAR(shift(1), -169. / 15500., 1e-12);
  EXPECT_NEAR(shift(0), -169. / 15500. - 169. / 7000., 1e-12);
}

TEST(MassChain, SpacedPantographsStartExactlyTheSpacingApart)
{
  // prm/scenes/two-pantographs.prm with Pantograph spacing = 2.5 m: pantograph
  // 2 starts at 6 - 2.5 = 3.5 m (its own Initial position = 6 is not read),
  // at pantograph 1's speed, and ends 2.5 m behind it. Exact (representable
  // numbers, one subtraction).
  const ProgramParameters p =
      read_case(source_file("prm/scenes/two-pantographs.prm"),
                {"Scene/Pantograph spacing=2.5", "Pantograph/Initial position=6",
                 "Pantograph/Final position=7", "Pantograph 2/Speed=20"});
  const auto& first = p.scene.pantographs[0].parameters;
  const auto& second = p.scene.pantographs[1].parameters;
  EXPECT_EQ(first.initial_position - second.initial_position, 2.5);
  EXPECT_EQ(first.final_position - second.final_position, 2.5);
  EXPECT_EQ(second.speed, first.speed);
  const auto points = run(p);
  ASSERT_GT(points.size(), 10u);
  EXPECT_EQ(points.front().x_p[0] - points.front().x_p[1], 2.5);
  // Same speed: the spacing stays (to the round-off of x_0 + v t, 1e-12 m).
  for (const TimePoint& point : points)
    ASSERT_NEAR(point.x_p[0] - point.x_p[1], 2.5, 1e-12) << "t = " << point.t;
}

TEST(MassChain, SpacingThatLeavesTheDomainIsRefused)
{
  // x_p1(0) = 2 m, three pantographs 1 m apart: pantograph 3 would start at
  // 0 m, outside (eps, L - eps) = (0.2, 19.8) m: refused naming the spacing.
  try
  {
    read_case(source_file("prm/scenes/two-pantographs.prm"),
              {"Scene/Number of pantographs=3", "Scene/Pantograph spacing=1"});
    FAIL() << "accepted";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(
        std::string(e.what()).find("Scene/Pantograph spacing = 1: puts pantograph 3"),
        std::string::npos)
        << e.what();
  }
}
