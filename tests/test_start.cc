// How a dynamic run starts (Run/Start; doc/dynamics.md, "How a run starts"):
// the static equilibrium of the whole system, or the paper's start (13).
#include <pantocat/pantograph/pantograph_parameters.h>
#include <pantocat/simulation/case_runner.h>
#include <pantocat/simulation/contact_statistics.h>

#include "support/case_files.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <iostream>

using namespace pantocat;

namespace
{
/// S60 (prm/catenary/simple-60m.prm) with @p overrides, up to x_p = 370 m
/// (the window, spans 5 and 6, ends at 360 m).
ProgramParameters s60(std::vector<std::string> overrides = {})
{
  overrides.push_back("Pantograph/Final position=370");
  return shipped_catenary("simple-60m.prm", overrides);
}

/// The same pantograph as S60's two-mass model, as a mass chain.
const std::vector<std::string> s60_as_a_mass_chain = {
    "Scene/Pantograph=mass-chain",
    "Pantograph/Mass-chain model/Masses=7.2, 15",
    "Pantograph/Mass-chain model/Stiffnesses=4200, 50",
    "Pantograph/Mass-chain model/Dampings=10, 90",
    "Pantograph/Mass-chain model/Static force=115",
    "Pantograph/Mass-chain model/Force body=2",
    "Pantograph/Mass-chain model/Reference state=relaxed springs"};

/// The contact force at every time point up to @p until, and the window's statistics.
struct StartRecord : SimulationObserver
{
  StartRecord(const unsigned int contact, const double until)
      : contact(contact), until(until)
  {
  }
  void observe(const TimePoint& p) override
  {
    if (p.t <= until)
      early.push_back(p.lambda[contact]);
  }
  unsigned int contact;
  double until;
  std::vector<double> early;
};

struct S60Run
{
  std::vector<double> early; ///< lambda_p over the first 0.1 s
  ContactForceStatistics statistics;
};

S60Run run_s60(const ProgramParameters& p)
{
  CaseRunner runner(p.make_case());
  StartRecord record(runner.layout().pantographs[0].contact, 0.1);
  ContactStatistics statistics(p.statistics, runner.discretisation(), runner.system());
  runner.run({&record, &statistics});
  return {record.early, statistics.result()};
}

double largest_departure(const std::vector<double>& force, const double reference)
{
  double d = 0.;
  for (const double f : force)
    d = std::max(d, std::abs(f - reference));
  return d;
}
} // namespace

TEST(Start, S60WithATwoMassPantographStartsWithoutAShock)
{
  // The case: S60, two-mass pantograph (static force 115 N, frame
  // spring 50 N/m, head damper 10 N s/m), from the anchor. To see the start
  // apart from the running dynamics, the train starts from rest with a 2 s
  // speed ramp to 300 km/h: the default start keeps the contact force within
  // 10 % of 115 N over the first 0.1 s (measured: 4.6 N), the paper's start
  // (13) with lambda_p(0) = 115 N gives the frame lambda_p(0) / d_1 relative
  // to the head, a shock far outside that band (measured: 2258 N), so the
  // check can fail. At full speed from t = 0 the default start leaves 115 N
  // by up to 85 N in the first 0.1 s (8.3 m into the first span: the section's
  // own dynamics, its window sigma is 33 N), the paper's start by 1600 N: the
  // shock is asserted below 10 % of the paper's.
  const std::vector<std::string> ramp = {"Pantograph/Speed ramp=2"};
  const std::vector<std::string> paper = {"Run/Start=paper",
                                          "Pantograph/Initial contact force=115"};
  std::vector<std::string> paper_ramp = paper;
  paper_ramp.push_back(ramp[0]);
  const double balanced = largest_departure(run_s60(s60(ramp)).early, 115.);
  const double shocked = largest_departure(run_s60(s60(paper_ramp)).early, 115.);
  const double at_speed = largest_departure(run_s60(s60()).early, 115.);
  const double paper_at_speed = largest_departure(run_s60(s60(paper)).early, 115.);
  std::cout << "  first 0.1 s, |lambda_p - 115 N| at most: with a 2 s ramp " << balanced
            << " N (static equilibrium), " << shocked << " N (paper); at full speed "
            << at_speed << " N, " << paper_at_speed << " N\n";
  EXPECT_LT(balanced, 0.1 * 115.);
  EXPECT_GT(shocked, 0.1 * 115.);
  EXPECT_LT(at_speed, 0.1 * paper_at_speed);
}

TEST(Start, S60IsTheSameWithTheSamePantographAsAMassChain)
{
  // The two-mass model and a mass chain of the same data are the same
  // equations (12); with the static-equilibrium start they start in the same
  // state, so the window's statistics agree to round-off (the issue asks for
  // 1 %; asserted to 1e-6 relative).
  const S60Run two_mass = run_s60(s60());
  const S60Run chain = run_s60(s60(s60_as_a_mass_chain));
  ASSERT_TRUE(two_mass.statistics.filtered && chain.statistics.filtered);
  const ForceFigures& a = *two_mass.statistics.filtered;
  const ForceFigures& b = *chain.statistics.filtered;
  std::cout << "  20 Hz window: mean " << a.mean << " / " << b.mean << " N, sigma "
            << a.std << " / " << b.std << " N\n";
  EXPECT_NEAR(b.mean, a.mean, 1e-6 * a.mean);
  EXPECT_NEAR(b.std, a.std, 1e-6 * a.std);
  EXPECT_NEAR(chain.statistics.raw.std, two_mass.statistics.raw.std,
              1e-6 * two_mass.statistics.raw.std);
}

TEST(Start, StaticEquilibriumIsAtRestUnderThePantographsForce)
{
  // S60's start: the catenary at rest (its accelerations vanish to
  // round-off: the static equilibrium K q = f + G^T lambda); the pantograph
  // moves as one body (w_p1' = w_p2'), its head spring carries the contact
  // force (c_1 (w_p2 - w_p1) = lambda_p(0)) and the contact force is the
  // pantograph's static force less its frame spring's, F_0 - c_2 w_p2.
  const ProgramParameters p = s60();
  const CaseRunner runner(p.make_case());
  const DynamicState& s = runner.initial_state();
  const PantographLayout& pantograph = runner.layout().pantographs[0];
  const DofBlock& block = runner.system().block(pantograph.name);
  const double w1 = s.q(block.first), w2 = s.q(block.first + 1);
  const double lambda = s.lambda[pantograph.contact];
  EXPECT_NEAR(4200. * (w2 - w1), lambda, 1e-9 * lambda);
  EXPECT_NEAR(lambda, 115. - 50. * w2, 1e-9 * lambda);
  EXPECT_EQ(s.v(block.first), s.v(block.first + 1));
  EXPECT_NEAR(pantograph.initial_contact_force, lambda, 0.);
  double largest = 0.;
  for (unsigned int i = 0; i < block.first; ++i)
    largest = std::max(largest, std::abs(s.a(i)));
  std::cout << "  lambda_p(0) = " << lambda << " N, w_p2(0) = " << w2
            << " m, largest catenary acceleration " << largest << " m/s^2\n";
  EXPECT_LT(largest, 1e-6); // 9.81 m/s^2 of gravity balanced to round-off
}

TEST(Start, SpeedsInKilometresPerHour)
{
  // Pantograph/Speed with its unit: 320 km/h is 320 / 3.6 m/s (the same
  // double as the division), "88.9 m/s" and a plain number are m/s; any
  // other unit is no speed.
  EXPECT_EQ(*speed_from_text("320 km/h"), 320. / 3.6);
  EXPECT_EQ(*speed_from_text(" 88.9 m/s "), 88.9);
  EXPECT_EQ(*speed_from_text("32"), 32.);
  EXPECT_FALSE(speed_from_text("320 kmh"));
  EXPECT_FALSE(speed_from_text("km/h"));
  EXPECT_EQ(s60({"Pantograph/Speed=250 km/h"}).pantograph().speed, 250. / 3.6);
}
