// Several pantographs on one catenary: numbers of pantographs and contacts
// are data (prm/scenes/two-pantographs.prm).
#include <pantocat/app/parameter_input.h>
#include <pantocat/app/program_parameters.h>
#include <pantocat/simulation/case_runner.h>
#include <pantocat/simulation/run_statistics.h>

#include "support/case_files.h"
#include "support/rigid_wire_response.h"

#include <gtest/gtest.h>

using namespace pantocat;

namespace
{
ProgramParameters shipped(const std::string& name,
                          const std::vector<std::string>& overrides = {})
{
  return read_case(source_file("prm/" + name), overrides);
}

struct Recorder : SimulationObserver
{
  void observe(const TimePoint& p) override { points.push_back(p); }
  std::vector<TimePoint> points;
};

struct CaseRun
{
  explicit CaseRun(const ProgramParameters& p) : runner(p.make_case())
  {
    result = runner.run({&record, &stats});
  }
  CaseRunner runner;
  Recorder record;
  RunStatistics stats;
  CaseRunner::Result result;
};
} // namespace

TEST(Pantographs, AnAbsentSecondPantographReproducesTheBenchmarkBitForBit)
{
  // The benchmark at 32 m/s (x_p from 2 to 6 m to keep it short) with one
  // pantograph, and again with a second one given as absent: no body, no
  // contact, no load. Every multiplier and the final state agree to the bit.
  const std::vector<std::string> shorter{"Pantograph/Final position=6"};
  auto with_second = shorter;
  with_second.insert(with_second.end(),
                     {"Scene/Number of pantographs=2", "Pantograph 2/Model=absent",
                      "Pantograph 2/Initial position=10",
                      "Pantograph 2/Final position=14"});
  const CaseRun one(shipped("benchmark-32.prm", shorter));
  const CaseRun two(shipped("benchmark-32.prm", with_second));
  ASSERT_EQ(two.runner.layout().pantographs.size(), 2u);
  EXPECT_FALSE(two.runner.layout().pantographs[1].has_contact());
  ASSERT_EQ(one.record.points.size(), two.record.points.size());
  for (std::size_t n = 0; n < one.record.points.size(); ++n)
  {
    EXPECT_EQ(one.record.points[n].lambda, two.record.points[n].lambda) << n;
    EXPECT_EQ(one.record.points[n].pantograph, two.record.points[n].pantograph) << n;
  }
  const auto& q1 = one.result.final_state.q;
  const auto& q2 = two.result.final_state.q;
  ASSERT_EQ(q1.size(), q2.size());
  for (unsigned int i = 0; i < q1.size(); ++i)
    ASSERT_EQ(q1(i), q2(i)) << i;
}

TEST(Pantographs, TwoPantographsOnARigidWireEachFollowTheClosedForm)
{
  // The rigid-wire scene with a second pantograph of its own data (another
  // initial force, offset and head damping): the bodies do not interact
  // through a rigid wire, so each follows its own damped frame oscillator.
  const ProgramParameters p = shipped(
      "scenes/pantograph-rigid-wire.prm",
      {"Scene/Number of pantographs=2", "Pantograph 2/Initial position=8",
       "Pantograph 2/Initial contact force=50", "Pantograph 2/Initial offset=-0.002",
       "Pantograph 2/Two-mass model/Head damping=45"});
  const CaseRun run(p);
  const auto& layout = run.runner.layout();
  ASSERT_EQ(layout.contacts().size(), 2u);
  for (unsigned int k = 0; k < 2; ++k)
  {
    const PantographParameters& data = p.scene.pantographs[k].parameters;
    const unsigned int contact = layout.pantographs[k].contact;
    const unsigned int head = layout.pantographs[k].first_coordinate;
    double error = 0.;
    for (const TimePoint& point : run.record.points)
    {
      error = std::max(error, std::abs(point.lambda[contact] -
                                       rigid_wire_contact_force(data, point.t)));
      EXPECT_LT(std::abs(point.pantograph[head]), 1e-12); // the head stays on the wire
    }
    // As for one pantograph (test_scenes): O((omega dt)^2) of the swing, 2e-4 N.
    EXPECT_LT(error, 2e-4) << "pantograph " << k + 1;
  }
}

TEST(Pantographs, TwoPantographsOnTheBenchmarkSpanKeepContact)
{
  // prm/scenes/two-pantographs.prm: x_p(0) = 2 and 6 m, 32 m/s, F_0 = 70 N
  // each. Measured: max 110.45 / 207.29 N, min 5.28 / 0.89 N, no loss.
  const CaseRun run(shipped("scenes/two-pantographs.prm"));
  const auto& layout = run.runner.layout();
  ASSERT_EQ(layout.contacts().size(), 2u);
  EXPECT_EQ(layout.pantographs[1].name, "pantograph 2");
  for (unsigned int k = 0; k < 2; ++k)
  {
    EXPECT_TRUE(run.stats.contact_loss_intervals(k).empty()) << k;
    // A unilateral contact that stays closed carries a positive force; both
    // means near F_0 = 70 N less what the catenary's stiffness takes
    // (the single pantograph's mean is 72.1 N): within 25 %.
    EXPECT_GT(run.stats.contact_force(k).min, 0.) << k;
    EXPECT_NEAR(run.stats.contact_force(k).mean, 70., 17.5) << k;
  }
  // The leading pantograph ends the run at 18 m: t_e = (18 - 6) / 32 s.
  EXPECT_NEAR(run.result.end_time, 0.375, 1e-12);
  EXPECT_NEAR(run.record.points.back().x_p[1], 18., 32. * 5e-5);
}
