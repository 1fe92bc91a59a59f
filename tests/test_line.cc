// Lines of tension sections joined by overlaps (doc/catenaries.md, "Lines of
// tension sections"): L3 of the data sheet, prm/catenary/line-three-sections.prm.
#include <pantocat/catenary/line_parameters.h>
#include <pantocat/simulation/case_runner.h>
#include <pantocat/space/catenary_discretisation.h>

#include "support/case_files.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace pantocat;

namespace
{
/// The forces of pantograph @p k on each contact wire at every time point.
struct WireForces : SimulationObserver
{
  explicit WireForces(const unsigned int k) : k(k) {}
  void start(const SimulationLayout& l) override
  {
    contacts = l.pantographs[k].wire_contacts;
  }
  void observe(const TimePoint& p) override
  {
    x.push_back(p.x_p[k]);
    std::vector<double> f;
    for (const unsigned int i : contacts)
      f.push_back(p.lambda[i]);
    force.push_back(f);
  }
  double total(const std::size_t n) const
  {
    double sum = 0.;
    for (const double f : force[n])
      sum += f;
    return sum;
  }
  unsigned int k;
  std::vector<unsigned int> contacts;
  std::vector<double> x;
  std::vector<std::vector<double>> force; ///< per time point, per contact wire
};

/// The dropper forces at every time point.
struct DropperForces : SimulationObserver
{
  void start(const SimulationLayout& l) override { droppers = l.dropper_indices; }
  void observe(const TimePoint& p) override
  {
    std::vector<double> f;
    for (const unsigned int i : droppers)
      f.push_back(p.lambda[i]);
    force.push_back(f);
  }
  std::vector<unsigned int> droppers;
  std::vector<std::vector<double>> force;
};

/// L3's section (S55 over 20 spans) as the shipped case reads it.
ProgramParameters l3(const std::vector<std::string>& overrides = {})
{
  return shipped_catenary("line-three-sections.prm", overrides);
}
} // namespace

TEST(Line, L3SectionsAsTheDataSheetPlacesThem)
{
  // ../shared/data/catenaries.md, L3: sections at 0, 935 and 1870 m; the
  // overlap's supports 17..20 of section k are 0..3 of section k+1; the
  // outgoing wire 0 up to the middle of span O1-O2, +0.20 m at O2, +0.50 m at
  // O3; the incoming wire mirrors it. Exact arithmetic on the data (1e-12 m).
  const ProgramParameters p = l3();
  const std::vector<CatenaryParameters> s = p.make_case().sections();
  ASSERT_EQ(s.size(), 3u);
  EXPECT_DOUBLE_EQ(s[1].start, 935.);
  EXPECT_DOUBLE_EQ(s[2].start, 1870.);
  EXPECT_DOUBLE_EQ(p.make_case().line_length(), 2970.);
  const std::vector<double> out{0., 0., 0.2, 0.5}, in{0.5, 0.2, 0., 0.};
  for (unsigned int i = 0; i < 4; ++i)
  {
    EXPECT_NEAR(s[0].support_heights[17 + i], out[i], 1e-12);
    EXPECT_NEAR(s[1].support_heights[i], in[i], 1e-12);
    EXPECT_NEAR(s[1].support_heights[17 + i], out[i], 1e-12);
    EXPECT_NEAR(s[2].support_heights[i], in[i], 1e-12);
  }
  EXPECT_NEAR(s[0].support_heights[16], 0., 1e-12);
  EXPECT_NEAR(s[2].support_heights[20], 0., 1e-12);
  // Section 1's droppers in span O1-O2 (990-1045 m): 0 up to the middle
  // 1017.5 m, then 0.2 (x - 1017.5) / 27.5; S55's pre-sag before the overlap.
  const auto target = [&](const CatenaryParameters& c, const double x)
  {
    for (unsigned int j = 0; j < c.n_droppers(); ++j)
      if (std::abs(c.dropper_positions[j] - x) < 1e-9)
        return c.dropper_target_heights()[j];
    ADD_FAILURE() << "no dropper at " << x;
    return 0.;
  };
  EXPECT_NEAR(target(s[0], 1011.75), 0., 1e-12);
  EXPECT_NEAR(target(s[0], 1017.5), 0., 1e-12);
  EXPECT_NEAR(target(s[0], 1023.25), 0.2 * 5.75 / 27.5, 1e-12);
  EXPECT_NEAR(target(s[0], 1049.5), 0.2 + 0.3 * 4.5 / 55., 1e-12);
  // The incoming wire mirrors it: section 2's x = 82.5 - d has the outgoing
  // wire's height at 82.5 + d from the overlap's start.
  EXPECT_NEAR(target(s[1], 1017.5 - 935. - 5.75), 0.2 * 5.75 / 27.5, 1e-12);
  EXPECT_NEAR(target(s[0], 4.5 + 55.), -4. * 0.055 * (4.5 / 55.) * (1. - 4.5 / 55.),
              1e-12);
}

TEST(Line, ReferenceHeightIsTheSupportChordUnderTheLoad)
{
  // The contact point's reference height int delta_eps(y - x) h(y) dy of the
  // support chord h, against a composite Simpson rule with 20000 panels
  // (error ~1e-13 m on the kinks' pieces); the derivatives against central
  // differences of the value (O(d^2) = 1e-8 relative with d = 1e-4 m).
  ProgramParameters p = l3({"Discretisation/Load shape=smoothed delta"});
  const CatenaryParameters c = p.make_case().sections()[0];
  const auto space = create_catenary_discretisation(c, p.discretisation);
  const SmoothedDelta& delta = space->smoothed_delta();
  const double eps = delta.epsilon();
  for (const double x : {1044.9, 1045., 1045.1, 1099.95, 1100.05, 1017.5, 500.})
  {
    const unsigned int n = 20000;
    double simpson = 0.;
    for (unsigned int i = 0; i <= n; ++i)
    {
      const double y = x - eps + 2. * eps * i / n;
      const double w = (i == 0 || i == n) ? 1. : (i % 2 ? 4. : 2.);
      simpson += w * delta.value(y - x) * c.support_chord(y);
    }
    simpson *= 2. * eps / n / 3.;
    EXPECT_NEAR(space->reference_height(x, 0), simpson, 1e-10) << "x = " << x;
    const double d = 1e-4;
    const double slope =
        (space->reference_height(x + d, 0) - space->reference_height(x - d, 0)) /
        (2. * d);
    EXPECT_NEAR(space->reference_height(x, 1), slope, 1e-7) << "x = " << x;
    const double curvature =
        (space->reference_height(x + d, 1) - space->reference_height(x - d, 1)) /
        (2. * d);
    EXPECT_NEAR(space->reference_height(x, 2), curvature, 1e-5) << "x = " << x;
  }
}

TEST(Line, ASectionOutOfReachLeavesTheOtherAlone)
{
  // Two sections of 6 spans with an overlap of 2 whose wires rise at once to
  // 1 m: the pantograph runs in section 1 up to x = 200 m, before the
  // overlap (220-330 m), and never reaches section 2's wire. The line then
  // is section 1 alone (the same section on its own, with the same heights):
  // the contact forces agree to round-off (1e-9 relative), and section 2's
  // droppers keep their static forces to the round-off of the static state
  // (1e-6 N of about 100 N).
  const std::vector<std::string> two{
      "Catenary/Number of spans=6",     "Discretisation/Number of intervals=660",
      "Line/Number of sections=2",      "Line/Overlap spans=2",
      "Line/Overlap heights=0, 0.6, 1", "Catenary/Droppers/Unreachable targets=refuse",
      "Pantograph/Final position=200",  "Statistics/Window spans="};
  const ProgramParameters line = shipped_catenary("section-s55.prm", two);
  Case alone = line.make_case();
  alone.catenary = alone.sections()[0];
  alone.catenary.name.clear();
  alone.line = {};

  CaseRunner on_line(line.make_case());
  WireForces line_forces(0);
  DropperForces droppers;
  on_line.run({&line_forces, &droppers});
  CaseRunner single(alone);
  WireForces single_forces(0);
  single.run({&single_forces});

  ASSERT_EQ(line_forces.force.size(), single_forces.force.size());
  double largest = 0., difference = 0.;
  for (std::size_t n = 0; n < line_forces.force.size(); ++n)
  {
    EXPECT_EQ(line_forces.force[n][1], 0.); // section 2's wire: out of reach
    largest = std::max(largest, single_forces.total(n));
    difference =
        std::max(difference, std::abs(line_forces.total(n) - single_forces.total(n)));
  }
  EXPECT_LT(difference, 1e-9 * largest);
  const std::size_t first_of_section_2 = droppers.droppers.size() / 2;
  double moved = 0.;
  for (const auto& f : droppers.force)
    for (std::size_t j = first_of_section_2; j < f.size(); ++j)
      moved = std::max(moved, std::abs(f[j] - droppers.force.front()[j]));
  EXPECT_LT(moved, 1e-6);
}

namespace
{
/// The leader's forces on each wire through overlap 1 of L3 at step @p dt.
WireForces leader_through_overlap_1(const double dt)
{
  const ProgramParameters p = l3(
      {"Pantograph/Initial position=900", "Pantograph/Final position=1050",
       "Statistics/Window spans=", "Time integration/Time step=" + std::to_string(dt)});
  CaseRunner runner(p.make_case());
  WireForces leader(0);
  runner.run({&leader});
  return leader;
}

/// The largest change of the total force from one time point to the next
/// while x_p lies in [@p x0, @p x1].
double largest_step(const WireForces& w, const double x0, const double x1)
{
  double d = 0.;
  for (std::size_t n = 1; n < w.x.size(); ++n)
    if (w.x[n] >= x0 && w.x[n] <= x1)
      d = std::max(d, std::abs(w.total(n) - w.total(n - 1)));
  return d;
}
} // namespace

TEST(Line, L3HandsThePantographOverAtTheFirstOverlap)
{
  // L3's leader through overlap 1 (935-1100 m). Each contact's force is
  // never negative (the penalty law); somewhere in the overlap both wires
  // carry the leader (the hand-over); and the total on both wires is
  // continuous through it: its largest change from one step to the next,
  // within 1 m of the hand-over, halves with the step (a continuous force
  // changes by O(dt) per step; a jump would not shrink): ratio below 0.6.
  const WireForces coarse = leader_through_overlap_1(2e-4),
                   fine = leader_through_overlap_1(1e-4);
  for (const WireForces* w : {&coarse, &fine})
    for (const auto& f : w->force)
      for (const double l : f)
        ASSERT_GE(l, 0.);
  std::size_t first = 0, last = 0;
  for (std::size_t n = 0; n < coarse.force.size(); ++n)
    if (coarse.force[n][0] > 0. && coarse.force[n][1] > 0.)
      last = n, first = first ? first : n;
  ASSERT_GT(last, 0u) << "no time point with both wires carrying the leader";
  EXPECT_GT(coarse.x[first], 935.);
  EXPECT_LT(coarse.x[last], 1100.);
  const double x0 = coarse.x[first] - 1., x1 = coarse.x[last] + 1.;
  const double ratio = largest_step(fine, x0, x1) / largest_step(coarse, x0, x1);
  std::cout << "hand-over at x_p = " << coarse.x[first] << " .. " << coarse.x[last]
            << " m; largest change of the total per step " << largest_step(coarse, x0, x1)
            << " N at dt = 2e-4 s, " << largest_step(fine, x0, x1)
            << " N at 1e-4 s (ratio " << ratio << ")\n";
  EXPECT_LT(ratio, 0.6);
}
