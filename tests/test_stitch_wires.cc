// The stitched catenary: S55 with stitch wires (S55-Y of doc/data-sheets.md,
// prm/catenary/section-s55-stitched.prm; doc/catenaries.md, "The stitched
// catenary").
#include <pantocat/analysis/static_elasticity.h>
#include <pantocat/base/input_error.h>
#include <pantocat/simulation/case_runner.h>

#include "support/case_files.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>

using namespace pantocat;

namespace
{
struct ContactForces : SimulationObserver
{
  explicit ContactForces(const unsigned int contact) : contact(contact) {}
  void observe(const TimePoint& p) override { lambda.push_back(p.lambda[contact]); }
  unsigned int contact;
  std::vector<double> lambda;
};

/// The contact force lambda_p at every time point of a run of @p p.
std::vector<double> contact_forces(const ProgramParameters& p)
{
  CaseRunner runner(p.make_case());
  ContactForces forces(runner.layout().pantographs[0].contact);
  runner.run({&forces});
  return forces.lambda;
}

double largest_difference(const std::vector<double>& a, const std::vector<double>& b)
{
  EXPECT_EQ(a.size(), b.size());
  double d = 0.;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i)
    d = std::max(d, std::abs(a[i] - b[i]));
  return d;
}

/// The designed dropper lengths of @p p.
std::vector<double> dropper_lengths(const ProgramParameters& p)
{
  return CaseRunner(p.make_case()).case_data().catenary.dropper_lengths;
}

/// S55's run over spans 1 to 3 (the pantograph from the anchor to x = 165 m):
/// three stitched supports, a third of the shipped run.
const std::vector<std::string> first_spans = {"Pantograph/Final position=165",
                                              "Statistics/Window spans="};

std::vector<std::string> with(std::vector<std::string> a,
                              const std::vector<std::string>& b)
{
  a.insert(a.end(), b.begin(), b.end());
  return a;
}
} // namespace

TEST(StitchWires, ZeroLengthReproducesS55)
{
  // A stitch wire of length 0 is no stitch wire: nothing of it is assembled,
  // so the stitched case with Length = 0 is S55's system, and its design and
  // run are S55's to the bit (tolerance 0).
  const std::vector<std::string> zero = {"Catenary/Stitch wire/Length=0"};
  const ProgramParameters plain = shipped_catenary("section-s55.prm", first_spans);
  const ProgramParameters stitched =
      shipped_catenary("section-s55-stitched.prm", with(first_spans, zero));
  EXPECT_TRUE(stitched.catenary.stitch_wires.empty());
  EXPECT_EQ(dropper_lengths(plain), dropper_lengths(stitched));
  EXPECT_EQ(largest_difference(contact_forces(plain), contact_forces(stitched)), 0.);
}

TEST(StitchWires, VanishingTensionAndMassReproduceS55)
{
  // Stitch wires of 8 m (no dropper inside: the nearest droppers are 4.5 m
  // from the support) with the data sheet's tension and mass times eps and no
  // clamp masses: the same wave speed, forces on the carrier of order eps.
  // Design and dynamics tend to S55's linearly in eps: the difference at
  // eps = 1e-4 is a tenth of that at 1e-3 (ratio 10 +- 1: linear; the
  // static solves' round-off, 1e-12 m, lies far below). Measured at eps =
  // 1e-4: 3.0e-7 m in the dropper lengths and 0.019 N in lambda_p (0.011 % of
  // F0 = 169 N); asserted below twice that.
  const ProgramParameters plain = shipped_catenary("section-s55.prm", first_spans);
  const std::vector<double> l0 = dropper_lengths(plain);
  const std::vector<double> f0 = contact_forces(plain);
  double length_difference[2], force_difference[2];
  const double eps[2] = {1e-3, 1e-4};
  for (unsigned int k = 0; k < 2; ++k)
  {
    const std::vector<std::string> small = {
        "Catenary/Stitch wire/Length=8",
        "Catenary/Stitch wire/Tension=" + std::to_string(2800. * eps[k]),
        "Catenary/Stitch wire/Mass per length=" + std::to_string(0.31 * eps[k]),
        "Catenary/Stitch wire/Clamp mass=0", "Catenary/Stitch wire/Dropper positions="};
    const ProgramParameters p =
        shipped_catenary("section-s55-stitched.prm", with(first_spans, small));
    ASSERT_EQ(p.catenary.stitch_wires.size(), 9u);
    EXPECT_TRUE(p.catenary.stitch_wires[4].droppers.empty());
    length_difference[k] = largest_difference(l0, dropper_lengths(p));
    force_difference[k] = largest_difference(f0, contact_forces(p));
    std::cout << std::setprecision(4) << "  eps = " << eps[k]
              << ": dropper lengths differ by " << length_difference[k]
              << " m, lambda_p by " << force_difference[k] << " N\n";
  }
  EXPECT_NEAR(length_difference[0] / length_difference[1], 10., 1.);
  EXPECT_NEAR(force_difference[0] / force_difference[1], 10., 1.);
  EXPECT_LT(length_difference[1], 6e-7);
  EXPECT_LT(force_difference[1], 0.04);
}

TEST(StitchWires, S55YMeetsTheContactWireTargets)
{
  // The shipped S55-Y (FEM, Hermite wires, h = 0.5 m): the static contact
  // wire lies on the pre-sag parabola at all 90 droppers, the 18 of the
  // stitch wires included, and at 0 at the 9 steady arms: the issue asks
  // 0.1 mm; the design is exact up to the static solves' round-off (measured
  // below 1e-9 m). The stitch wire hangs below the carrier between its
  // clamps (its droppers pull it down), and the section stays symmetric
  // about x = 275 m (round-off, 1e-9 m).
  const CaseRunner runner(shipped_catenary("section-s55-stitched.prm").make_case());
  const CatenaryParameters& c = runner.case_data().catenary;
  ASSERT_EQ(c.stitch_wires.size(), 9u);
  const StaticEquilibrium s = runner.static_catenary();
  double worst = 0.;
  for (unsigned int j = 0; j < c.n_droppers(); ++j)
  {
    const double x = c.dropper_positions[j];
    const double xi = (x - 55. * c.dropper_spans[j]) / 55.;
    worst = std::max(worst, std::abs(runner.contact_wire_displacement(s.q, x) +
                                     4. * 0.055 * xi * (1. - xi)));
    EXPECT_GT(c.dropper_lengths[j], 0.);
  }
  for (const double x : c.steady_arm_positions())
    worst = std::max(worst, std::abs(runner.contact_wire_displacement(s.q, x)));
  std::cout << "  largest distance from the targets: " << worst << " m\n";
  EXPECT_LT(worst, 1e-4);
  for (unsigned int j = 0; j < 45; ++j)
    EXPECT_NEAR(c.dropper_lengths[j], c.dropper_lengths[89 - j], 1e-9) << j;

  // The stitch wire at support 5 (x = 275 m) at its droppers and at the
  // support, against the carrier at its clamps (heights above the contact
  // wire's working height 0).
  const CatenaryDiscretisation& d = runner.discretisation();
  const StitchWire& w = c.stitch_wires[4];
  const auto stitch = [&](const double x)
  { return c.support_height + stitch_wire_point_row(d, runner.system(), 4, x).dot(s.q); };
  const auto carrier = [&](const double x)
  {
    return c.support_height +
           wire_point_row(d, runner.system(), Wire::carrier, x).dot(s.q);
  };
  std::cout << "  stitch wire at support 5: clamps " << stitch(w.start())
            << " m, droppers " << stitch(w.centre - 4.5) << " m, support "
            << stitch(w.centre) << " m (carrier " << carrier(w.centre) << " m)\n";
  // Clamped: the carrier's height at both ends (round-off of the saddle-point solve).
  EXPECT_NEAR(stitch(w.start()), carrier(w.start()), 1e-9);
  EXPECT_NEAR(stitch(w.end()), carrier(w.end()), 1e-9);
  // Below the fixed carrier at the support; pulled down at its droppers
  // (measured: clamps 0.898 m, droppers 0.778 m), and between them sagging
  // under its own weight alone (0.767 m at the support).
  EXPECT_LT(stitch(w.centre), carrier(w.centre));
  EXPECT_LT(stitch(w.centre - 4.5), stitch(w.start()));
  EXPECT_LT(stitch(w.centre), stitch(w.centre - 4.5));
}

namespace
{
/// The static elasticity of span 5 of @p name at h = 0.25 m, 21 points, 100 N.
StaticElasticity span_5_elasticity(const std::string& name)
{
  const ProgramParameters p =
      shipped_catenary(name, {"Discretisation/Number of intervals=2200",
                              "Elasticity/Span=5", "Elasticity/Forces=100"});
  return CaseRunner(p.make_case()).static_elasticity(p.elasticity);
}
} // namespace

TEST(StitchWires, S55YIsMoreUniformInElasticityThanS55)
{
  // The static check of doc/elasticity.md on span 5 (x = 220 to 275 m,
  // 21 points, 100 N, h = 0.25 m) of S55 and S55-Y. The stitch wire makes
  // the support softer (the contact wire's droppers next to it hang from a
  // wire of 2 800 N instead of the messenger held at the support), mid-span
  // hardly changes, so (e_max - e_min)/(e_max + e_min) falls. Asserted: the
  // figures measured, to 1e-3 relative (a change of the grid, the design or
  // the solvers shows; round-off moves them by 1e-10), and S55-Y's
  // uniformity below S55's.
  const StaticElasticity plain = span_5_elasticity("section-s55.prm");
  const StaticElasticity stitched = span_5_elasticity("section-s55-stitched.prm");
  const std::vector<double> e0 = plain.elasticity(0), e1 = stitched.elasticity(0);
  const ElasticityFigures f0 = plain.figures(0), f1 = stitched.figures(0);
  std::cout << std::setprecision(4) << "  S55:   support " << e0.front() << ", mid-span "
            << e0[10] << ", e_min " << f0.minimum << ", e_max " << f0.maximum
            << " mm/N, uniformity " << f0.uniformity << "\n  S55-Y: support "
            << e1.front() << ", mid-span " << e1[10] << ", e_min " << f1.minimum
            << ", e_max " << f1.maximum << " mm/N, uniformity " << f1.uniformity << '\n';
  EXPECT_NEAR(f0.uniformity, 0.4959, 1e-3 * 0.4959);
  EXPECT_NEAR(f1.uniformity, 0.3557, 1e-3 * 0.3557);
  EXPECT_NEAR(e0.front(), 0.13726, 1e-3 * 0.13726);
  EXPECT_NEAR(e1.front(), 0.19706, 1e-3 * 0.19706);
  EXPECT_NEAR(e0[10], 0.38548, 1e-3 * 0.38548);
  EXPECT_NEAR(e1[10], 0.39273, 1e-3 * 0.39273);
  EXPECT_LT(f1.uniformity, f0.uniformity);
}

TEST(StitchWires, FdmCarriesTheStitchWiresToo)
{
  // FDM (h = 0.25 m): the stitch wires' mass lumped to their nodes (M stays
  // diagonal), droppers and clamps on the nearest nodes. The design meets the
  // targets at the contact wire's nodes to round-off (asserted 0.1 mm, the
  // issue's figure), and the run over the first three spans (three stitched
  // supports) keeps every unilateral force >= 0 (the laws: tolerance 0).
  const ProgramParameters p =
      shipped_catenary("section-s55-stitched.prm",
                       with(first_spans, {"Discretisation/Method=fdm",
                                          "Discretisation/Number of intervals=2200"}));
  CaseRunner runner(p.make_case());
  EXPECT_TRUE(runner.system().mass_is_diagonal);
  const CatenaryParameters& c = runner.case_data().catenary;
  const StaticEquilibrium s = runner.static_catenary();
  double worst = 0.;
  for (unsigned int j = 0; j < c.n_droppers(); ++j)
  {
    const double x = c.dropper_positions[j];
    const double xi = (x - 55. * c.dropper_spans[j]) / 55.;
    worst = std::max(worst, std::abs(runner.contact_wire_displacement(s.q, x) +
                                     4. * 0.055 * xi * (1. - xi)));
  }
  std::cout << "  FDM: largest distance from the targets " << worst << " m\n";
  EXPECT_LT(worst, 1e-4);

  struct Smallest : SimulationObserver
  {
    explicit Smallest(const SemiDiscreteSystem& system) : system(system) {}
    void observe(const TimePoint& t) override
    {
      for (unsigned int i = 0; i < t.lambda.size(); ++i)
        if (system.constraints[i]->is_unilateral())
          smallest = std::min(smallest, t.lambda[i]);
    }
    const SemiDiscreteSystem& system;
    double smallest = INFINITY;
  } smallest(runner.system());
  runner.run({&smallest});
  EXPECT_GE(smallest.smallest, 0.);
}
