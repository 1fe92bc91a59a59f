// No written force of a unilateral constraint is negative (doc/impacts.md):
// the cases where one was written, each run to its end through the case
// runner (every time point, not only the written ones), and the output
// path's last line of defence.
#include <pantocat/base/input_error.h>
#include <pantocat/simulation/case_runner.h>

#include "support/case_files.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

using namespace pantocat;

namespace
{
/// The smallest force of each rigid and each compliant unilateral constraint
/// over every time point of a run, and where it was.
struct SmallestForces : SimulationObserver
{
  explicit SmallestForces(const SemiDiscreteSystem& system) : system(system) {}
  void observe(const TimePoint& p) override
  {
    ++points;
    for (unsigned int i = 0; i < p.lambda.size(); ++i)
      if (system.constraints[i]->is_unilateral() && p.lambda[i] < smallest)
      {
        smallest = p.lambda[i];
        at = p.t;
        constraint = system.constraints[i]->name();
      }
  }
  const SemiDiscreteSystem& system;
  double smallest = INFINITY, at = NAN;
  std::string constraint;
  unsigned long points = 0;
};

/// Runs case @p file with @p overrides to its end: the smallest unilateral
/// force; the run must complete (a negative force stops it, CaseRunner::time_point()).
SmallestForces run_case(const std::string& file,
                        const std::vector<std::string>& overrides,
                        CaseRunner::Result* result = nullptr)
{
  std::filesystem::current_path(PANTOCAT_SOURCE_DIR); // prm includes, as for a user
  CaseRunner runner(read_case(source_file(file), overrides).make_case());
  SmallestForces smallest(runner.system());
  CaseRunner::Result r;
  EXPECT_NO_THROW(r = runner.run({&smallest}));
  EXPECT_EQ(smallest.points, runner.number_of_steps() + 1);
  if (result)
    *result = r;
  return smallest;
}
} // namespace

// Each case below wrote a negative force before the Richardson start of
// BDF-2 after an impact checked its extrapolated step (Bdf2Integrator):
// the extrapolation 2 x_{dt/2} - x_dt of two backward Euler results that
// each satisfied Sec. 5.3 gave a force of -2 lambda_dt where the step with
// dt held a constraint with force and the steps with dt/2 let it touch.
// The bound is exactly 0: an accepted step's multipliers of the active rigid
// unilateral constraints are >= 0 by the active-set iteration's own test
// (a negative one is released and the step repeated), the other unilateral
// constraints' forces are 0, and the compliant ones' max(0, ...); nothing
// is rounded after that test.

TEST(UnilateralForces, Benchmark48OnFemWithBdf2)
{
  // Was lambda_d2 = -1.09 N at t = 0.3247 s.
  const SmallestForces s = run_case(
      "prm/benchmark-48.prm", {"Discretisation/Method=fem",
                               "Time integration/Integrator=bdf2", "Output/Plots=false"});
  EXPECT_GE(s.smallest, 0.) << s.constraint << " at t = " << s.at;
}

TEST(UnilateralForces, Benchmark48OnACoarseFemGridWithBdf2)
{
  // N+1 = 250, dt = 1e-4 s: was lambda_p = -44.86 N at t = 0.26065 s.
  const SmallestForces s =
      run_case("prm/benchmark-48.prm",
               {"Discretisation/Method=fem", "Time integration/Integrator=bdf2",
                "Discretisation/Number of intervals=250",
                "Time integration/Time step=1e-4", "Output/Plots=false"});
  EXPECT_GE(s.smallest, 0.) << s.constraint << " at t = " << s.at;
}

TEST(UnilateralForces, TwoPantographsOnFemWithBdf2)
{
  // prm/scenes/two-pantographs.prm on FEM: was lambda_d2 = -51.05 N at t = 0.3456 s.
  const SmallestForces s =
      run_case("prm/scenes/two-pantographs.prm",
               {"Discretisation/Method=fem", "Time integration/Integrator=bdf2",
                "Output/Plots=false"});
  EXPECT_GE(s.smallest, 0.) << s.constraint << " at t = " << s.at;
}

TEST(UnilateralForces, FourSpansOfS55WithRigidContactAt200MetresPerSecond)
{
  // section-s55.prm cut to 4 spans (h = 0.5 m as shipped), rigid contact,
  // 200 m/s, BDF-2 at the shipped dt = 2e-4 s: was lambda_p = -104.9 N at
  // t = 0.1 s.
  const SmallestForces s =
      run_case("prm/catenary/section-s55.prm",
               {"Catenary/Number of spans=4", "Discretisation/Number of intervals=440",
                "Scene/Contact=unilateral", "Pantograph/Speed=200",
                "Pantograph/Final position=220", "Statistics/Window spans=2,3",
                "Time integration/Integrator=bdf2", "Output/Plots=false"});
  EXPECT_GE(s.smallest, 0.) << s.constraint << " at t = " << s.at;
}

TEST(UnilateralForces, ANegativeForceStopsTheRunWhereItArrives)
{
  // The output path's last line of defence: a state whose rigid unilateral
  // force is negative is an internal error, named with time, constraint and
  // value, never a time point.
  std::filesystem::current_path(PANTOCAT_SOURCE_DIR);
  const CaseRunner runner(
      read_case(source_file("prm/benchmark-48.prm"), {"Output/Plots=false"}).make_case());
  DynamicState s = runner.initial_state();
  const TimePoint fine = runner.time_point(s);
  EXPECT_EQ(fine.lambda, s.lambda);
  const std::vector<std::string>& names = runner.layout().constraint_names;
  const unsigned int d2 =
      std::find(names.begin(), names.end(), "dropper 2") - names.begin();
  ASSERT_LT(d2, names.size());
  s.t = 0.3247;
  s.lambda[d2] = -1.09;
  try
  {
    runner.time_point(s);
    FAIL() << "a negative force of dropper 2 became a time point";
  }
  catch (const SimulationError& e)
  {
    EXPECT_EQ(std::string(e.what()),
              "internal error at t = 0.3247 s: the force of the unilateral constraint "
              "dropper 2 is -1.09 N, but a unilateral constraint only pushes (lambda >= "
              "0, Sec. 5.3): the integrator's step is inconsistent, and this time point "
              "is not written");
  }
  // Zero is a force a unilateral constraint may have (slack, or touching).
  s.lambda[d2] = 0.;
  EXPECT_NO_THROW(runner.time_point(s));
}
