// The targets of the static design (doc/catenaries.md, "The static design"):
// the pre-sag parabola zero at the supports or at the first and last dropper
// of each span (Catenary/Droppers/Pre-sag reference), or target heights given
// per dropper (Catenary/Droppers/Target heights), and their refusals.
#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>
#include <pantocat/simulation/case_runner.h>

#include "support/case_files.h"
#include "support/input_errors.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace pantocat;

namespace
{
/// S55 (section-s55.prm) on three spans (27 elastic droppers, 2 steady arms),
/// h = 0.5 m as shipped, with @p method and the @p overrides.
ProgramParameters s55(const std::string& method,
                      const std::vector<std::string>& overrides)
{
  std::vector<std::string> all{
      "Catenary/Number of spans=3", "Discretisation/Method=" + method,
      "Discretisation/Number of intervals=330", "Pantograph/Final position=160",
      "Statistics/Window spans="};
  all.insert(all.end(), overrides.begin(), overrides.end());
  return shipped_catenary("section-s55.prm", all);
}

/// S55's droppers in a span [m from its first support].
const std::vector<double> s55_droppers = {4.5,   10.25, 16.0,  21.75, 27.5,
                                          33.25, 39.0,  44.75, 50.5};

/// z = -4 s xi (1 - xi) at S55's dropper @p i of a span, xi from 0 to 1 over
/// [@p x0, @p x1] (the parabola written out here, not taken from the program).
double parabola(const double s, const double x0, const double x1, const unsigned int i)
{
  const double xi = (s55_droppers[i] - x0) / (x1 - x0);
  return -4. * s * xi * (1. - xi);
}

/// The entry "Catenary/Droppers/Target heights=..." with @p z to round-trip digits.
std::string target_heights(const std::vector<double>& z)
{
  std::string list;
  for (const double v : z)
    list += (list.empty() ? "" : ", ") + number_to_string(v, 17);
  return "Catenary/Droppers/Target heights=" + list;
}

/// Largest |w_w(x_j) - z_j| of the static catenary designed by @p runner,
/// z_j = @p targets[j % targets.size()] (one per dropper of a span, or of the section).
double largest_miss(const CaseRunner& runner, const std::vector<double>& targets)
{
  const CatenaryParameters& c = runner.case_data().catenary;
  const StaticEquilibrium s = runner.static_catenary();
  double miss = 0.;
  for (unsigned int j = 0; j < c.n_droppers(); ++j)
    miss = std::max(
        miss, std::abs(runner.contact_wire_displacement(s.q, c.dropper_positions[j]) -
                       targets[j % targets.size()]));
  return miss;
}

/// The designed lengths of the case @p p.
std::vector<double> designed_lengths(const ProgramParameters& p)
{
  return CaseRunner(p.make_case()).case_data().catenary.dropper_lengths;
}

/// The message of the InputError that reading F3 with @p overrides throws.
std::string refusal(const std::vector<std::string>& overrides)
{
  return input_error_of([&] { shipped_catenary("paper-fig3.prm", overrides); });
}
} // namespace

TEST(TargetHeights, S55MeetsItsPreSagInBothReferences)
{
  // S55's data, pre-sag s = 0.055 m, zero at the supports (z from x = 0 to
  // 55 m of the span) or at the first and last dropper (from 4.5 to 50.5 m),
  // FEM and FDM: the static contact wire at every dropper lies on the
  // parabola written out here. The issue asks 0.1 mm; the design holds the
  // wire at its targets and is exact up to the round-off of the static
  // solves, so 1e-9 m is asserted (measured: 4e-14 m). The two references
  // give different targets (the first dropper at -16.5 mm or at 0).
  for (const std::string method : {"fem", "fdm"})
    for (const bool supports : {true, false})
    {
      const std::string reference = supports ? "supports" : "first and last dropper";
      const ProgramParameters p =
          s55(method, {"Catenary/Droppers/Pre-sag=0.055",
                       "Catenary/Droppers/Pre-sag reference=" + reference});
      std::vector<double> z;
      for (unsigned int i = 0; i < s55_droppers.size(); ++i)
        z.push_back(supports ? parabola(0.055, 0., 55., i)
                             : parabola(0.055, 4.5, 50.5, i));
      const CaseRunner runner(p.make_case());
      ASSERT_EQ(runner.case_data().catenary.n_droppers(), 27u);
      const double miss = largest_miss(runner, z);
      std::cout << "  " << method << ", zero at the " << reference << ": largest miss "
                << miss << " m\n";
      EXPECT_LT(miss, 1e-9) << method << ", " << reference;
    }
}

TEST(TargetHeights, S55MeetsItsPreSagBelowTheChordOfRaisedSupports)
{
  // S55 on three spans with the contact wire raised to 0.3 m at the two
  // interior supports (Catenary/Supports/Contact wire heights = 0, 0.3, 0.3,
  // 0; the messenger 1.2 m above each): both wires run on the straight
  // chord between the support heights, and the design puts the static
  // contact wire the pre-sag parabola below it at every dropper, and on the
  // chord at the steady arms; exact to the static solves' round-off
  // (1e-9 m asserted, as above).
  for (const std::string method : {"fem", "fdm"})
  {
    const ProgramParameters p =
        s55(method, {"Catenary/Droppers/Pre-sag=0.055",
                     "Catenary/Supports/Contact wire heights=0, 0.3, 0.3, 0"});
    std::vector<double> z;
    for (unsigned int i = 0; i < s55_droppers.size(); ++i)
      z.push_back(parabola(0.055, 0., 55., i));
    const CaseRunner runner(p.make_case());
    const CatenaryParameters& c = runner.case_data().catenary;
    EXPECT_NEAR(c.support_chord(27.5), 0.15, 1e-15);
    EXPECT_NEAR(c.dropper_target_heights()[4], 0.15 - 0.055, 1e-15);
    EXPECT_LT(largest_miss(runner, z), 1e-9) << method;
    const StaticEquilibrium s = runner.static_catenary();
    for (const double x : {55., 110.})
      EXPECT_NEAR(runner.contact_wire_displacement(s.q, x), 0., 1e-9) << method << x;
  }
}

TEST(TargetHeights, S55MeetsTargetsGivenPerDropper)
{
  // Target heights given per dropper of a span (9, reused in every span) and
  // per dropper of the section (27, each span its own), not a parabola: an
  // uneven profile, deepest (30 mm) at the seventh dropper, and spans sagging
  // by 0, 20 and 40 mm at mid-span. FEM and FDM; the static contact wire
  // at every dropper on its target, to 1e-9 m (the issue asks 0.1 mm; the
  // design is exact up to round-off; measured: 4e-14 m).
  const std::vector<double> span = {-0.01,  -0.02, -0.02, -0.02, -0.02,
                                    -0.025, -0.03, -0.02, -0.01};
  std::vector<double> section;
  for (unsigned int k = 0; k < 3; ++k)
    for (unsigned int i = 0; i < 9; ++i)
      section.push_back(-0.02 * k * std::sin(M_PI * (i + 1) / 10.));
  for (const std::string method : {"fem", "fdm"})
    for (const std::vector<double>& z : {span, section})
    {
      const CaseRunner runner(
          s55(method, {"Catenary/Droppers/Pre-sag=0", target_heights(z)}).make_case());
      const double miss = largest_miss(runner, z);
      std::cout << "  " << method << ", " << z.size() << " heights: largest miss " << miss
                << " m\n";
      EXPECT_LT(miss, 1e-9) << method << ", " << z.size();
      EXPECT_EQ(runner.case_data().catenary.dropper_target_heights().size(), 27u);
    }
}

TEST(TargetHeights, TargetsOnThePreSagParabolaGiveThePreSagDesign)
{
  // The pre-sag parabola (s = 0.055 m, both references) written out as
  // Target heights, one per dropper of a span: the same targets to the last
  // digit or so, hence the same lengths up to the round-off of the design
  // (asserted: 1e-9 m; measured: equal), FEM.
  for (const bool supports : {true, false})
  {
    const std::string reference = supports ? "supports" : "first and last dropper";
    std::vector<double> z;
    for (unsigned int i = 0; i < s55_droppers.size(); ++i)
      z.push_back(supports ? parabola(0.055, 0., 55., i) : parabola(0.055, 4.5, 50.5, i));
    const std::vector<double> from_presag = designed_lengths(
        s55("fem", {"Catenary/Droppers/Pre-sag=0.055",
                    "Catenary/Droppers/Pre-sag reference=" + reference}));
    const std::vector<double> from_targets =
        designed_lengths(s55("fem", {"Catenary/Droppers/Pre-sag=0", target_heights(z)}));
    ASSERT_EQ(from_presag.size(), 27u);
    ASSERT_EQ(from_targets.size(), 27u);
    double largest = 0.;
    for (unsigned int j = 0; j < 27; ++j)
      largest = std::max(largest, std::abs(from_targets[j] - from_presag[j]));
    std::cout << "  zero at the " << reference << ": lengths differ by up to " << largest
              << " m\n";
    for (unsigned int j = 0; j < 27; ++j)
      EXPECT_NEAR(from_targets[j], from_presag[j], 1e-9)
          << reference << ", dropper " << j + 1;
  }
}

TEST(TargetHeights, ASpanWithOneDropperHasNoFirstAndLastDropper)
{
  // F3 on two spans, the second with one dropper: the parabola zero at the
  // first and last dropper does not exist there; refused with the reference
  // named. A span without droppers needs no targets and is accepted.
  const std::vector<std::string> common{
      "Catenary/Number of spans=2",
      "Catenary/Droppers/Pre-sag reference=first and last dropper"};
  std::vector<std::string> one = common, none = common;
  one.push_back("Catenary/Droppers/Positions=5.5, 32.5, 59.5; 32.5");
  none.push_back("Catenary/Droppers/Positions=5.5, 32.5, 59.5;");
  EXPECT_EQ(refusal(one),
            "Catenary/Droppers/Pre-sag reference = first and last dropper: span 2 has 1 "
            "dropper, and the parabola is zero at two; allowed: supports, or at least 2 "
            "droppers in every span that has droppers");
  EXPECT_EQ(refusal(none), "");
}

TEST(TargetHeights, APreSagTogetherWithTargetHeightsIsRefused)
{
  // F3 (7 droppers in its one span): the heights replace the pre-sag, so a
  // pre-sag > 0 with them is a contradiction, refused in one line.
  EXPECT_EQ(
      refusal({"Catenary/Droppers/Pre-sag=0.065",
               "Catenary/Droppers/Target heights=0, -0.03, -0.05, -0.06, -0.05, "
               "-0.03, 0"}),
      "Catenary/Droppers/Pre-sag = 0.065: not together with Catenary/Droppers/Target "
      "heights (7 heights given): the heights replace the pre-sag; allowed: Pre-sag "
      "= 0 with Target heights, or no Target heights");
}

TEST(TargetHeights, AWrongNumberOfTargetHeightsIsRefused)
{
  // F3 on two spans, 7 droppers each: 7 (a span's) or 14 (the section's)
  // heights are allowed; with one list of positions per span only 14.
  EXPECT_EQ(
      refusal(
          {"Catenary/Number of spans=2", "Catenary/Droppers/Target heights=0, -0.01, 0"}),
      "Catenary/Droppers/Target heights = 0, -0.01, 0: 3 heights given; allowed: one "
      "per dropper of a span (7) or of the section (14), or none (the pre-sag's "
      "targets)");
  EXPECT_EQ(
      refusal({"Catenary/Number of spans=2",
               "Catenary/Droppers/Positions=5.5, 59.5; 5.5, 32.5, 59.5",
               "Catenary/Droppers/Target heights=0, -0.01"}),
      "Catenary/Droppers/Target heights = 0, -0.01: 2 heights given; allowed: one per "
      "dropper of the section (5), or none (the pre-sag's targets)");
  EXPECT_EQ(refusal({"Catenary/Number of spans=2",
                     "Catenary/Droppers/Target heights=0, -0.01, -0.02, -0.03, -0.02, "
                     "-0.01, 0"}),
            "");
}

TEST(TargetHeights, TargetsTheDroppersCannotProduceAreRefused)
{
  // F3 (l_c = 1 m) with the contact wire 2 m up at every dropper, above the
  // carrier: the design would need droppers of negative length; with it 2 m
  // up at dropper 4 only, its neighbours would have to push the wire down.
  // Each refused naming the entry, the dropper's target and where it is.
  const auto design = [](const std::string& targets)
  {
    return input_error_of(
        [&]
        {
          CaseRunner(shipped_catenary("paper-fig3.prm",
                                      {"Scene/Pantograph=absent",
                                       "Catenary/Droppers/Target heights=" + targets})
                         .make_case());
        });
  };
  const std::string above = design("2, 2, 2, 2, 2, 2, 2");
  EXPECT_EQ(above.rfind("Catenary/Droppers/Target heights = 2 (dropper 1): the design "
                        "gives dropper 1 at x = 5.5 m the length -",
                        0),
            0u)
      << above;
  EXPECT_NE(above.find("m; allowed: targets the droppers can produce (lower, or a larger "
                       "Encumbrance)"),
            std::string::npos)
      << above;
  const std::string bump = design("0, 0, 0, 2, 0, 0, 0");
  EXPECT_EQ(
      bump.rfind("Catenary/Droppers/Target heights = 0 (dropper 3): the design needs "
                 "dropper 3 at x = 23.5 m to push (-",
                 0),
      0u)
      << bump;
  EXPECT_NE(bump.find("N); allowed: targets the droppers can hold in tension"),
            std::string::npos)
      << bump;
}
