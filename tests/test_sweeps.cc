// Sweeps (issue 18): the value lists and ranges of subsection Sweep and their
// refusals, the Monte Carlo deviations (distribution, reproducibility), the
// installed catenary, the rows of a sweep's CSV and their transfer between
// MPI ranks, the percentiles of a Monte Carlo distribution, and a sweep's run
// against the single run of the same case.
#include <pantocat/app/program_parameters.h>
#include <pantocat/simulation/case_runner.h>
#include <pantocat/simulation/contact_statistics.h>
#include <pantocat/studies/sweep_plots.h>
#include <pantocat/studies/sweep_run.h>
#include <pantocat/studies/sweep_study.h>

#include <support/input_errors.h>

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

using namespace pantocat;

namespace
{
/// Mean and population standard deviation of @p x.
std::pair<double, double> mean_and_std(const std::vector<double>& x)
{
  const double mean = std::accumulate(x.begin(), x.end(), 0.) / x.size();
  double var = 0.;
  for (const double v : x)
    var += (v - mean) * (v - mean) / x.size();
  return {mean, std::sqrt(var)};
}

/// Every dropper deviation of @p n samples (90 droppers each, S55's count).
std::vector<double> dropper_deviations(const SweepParameters& p, const unsigned int n)
{
  std::vector<double> all;
  for (unsigned int i = 0; i < n; ++i)
  {
    const InstallationDeviations d = sample_deviations(p, 90, 9, i);
    all.insert(all.end(), d.dropper_lengths.begin(), d.dropper_lengths.end());
  }
  return all;
}

/// The paper's case on a coarse FDM grid (N+1 = 200), 32 m/s from 2 to 6 m, 20 Hz low
/// pass.
SweepCase small_case()
{
  ProgramParameters p;
  p.discretisation.method = SpaceMethod::fdm;
  p.discretisation.n_intervals = 200;
  p.time_integration.integrator = "half-explicit";
  p.time_integration.time_step = 1e-4;
  p.pantograph().final_position = 6.;
  p.statistics.low_pass_cutoff = 20.;
  return {p.make_case(), p.statistics};
}
} // namespace

TEST(SweepValues, RangesIncludeTheirLastValueAndListsAreKept)
{
  // 200 to 400 step 20 km/h: 11 speeds, 200 and 400 included (first + 10 x 20
  // is exact in binary: 1e-12 allows nothing but round-off).
  const std::vector<double> v = parse_sweep_values("200 to 400 step 20", "Sweep/Speeds");
  ASSERT_EQ(v.size(), 11u);
  EXPECT_NEAR(v.front(), 200., 1e-12);
  EXPECT_NEAR(v[5], 300., 1e-12);
  EXPECT_NEAR(v.back(), 400., 1e-12);
  // 0.1 + 2 x 0.1 is 0.30000000000000004 > 0.3: the 1e-9 slack keeps the last value.
  EXPECT_EQ(parse_sweep_values("0.1 to 0.3 step 0.1", "Sweep/Values").size(), 3u);
  // A range of one value.
  EXPECT_EQ(parse_sweep_values("320 to 320 step 20", "Sweep/Speeds").size(), 1u);
  const std::vector<double> list = parse_sweep_values("250, 320, 280", "Sweep/Speeds");
  EXPECT_EQ(list, (std::vector<double>{250., 320., 280.}));
}

TEST(SweepValues, EmptyRangesAndNonNumbersAreRefusedNamingTheParameter)
{
  const auto refusal = [](const std::string& text)
  { return input_error_of([&] { parse_sweep_values(text, "Sweep/Speeds"); }); };
  EXPECT_EQ(refusal("400 to 200 step 20"),
            "Sweep/Speeds = 400 to 200 step 20: an empty range; allowed: a list \"a, b, "
            "c\" or a range \"first to last step s\" with first <= last and s > 0");
  EXPECT_NE(refusal("200 to 400 step 0")
                .find("Sweep/Speeds = 200 to 400 step 0: an "
                      "empty range"),
            std::string::npos);
  EXPECT_NE(refusal("200 to 400 step -20").find("an empty range"), std::string::npos);
  EXPECT_NE(refusal("").find("Sweep/Speeds = : an empty list"), std::string::npos);
  EXPECT_NE(
      refusal("200, fast").find("Sweep/Speeds = 200, fast: \"fast\" is not a number"),
      std::string::npos);
  EXPECT_NE(refusal("200 to 400").find("Sweep/Speeds = 200 to 400: a list"),
            std::string::npos);
}

TEST(MonteCarlo, UniformDeviationsHaveTheRequestedMeanSpreadAndBound)
{
  // 2000 samples x 90 droppers = 180 000 draws, uniform in [-10, 10] mm:
  // std = 10 mm / sqrt(3) = 5.774 mm. Statistical tolerances of 4 standard
  // errors: mean 4 x 5.774e-3 / sqrt(180000) = 5.4e-5 m; std relative
  // 4 x sqrt((9/5 - 1) / (4 n)) = 0.42 % (the uniform's kurtosis is 9/5).
  SweepParameters p;
  p.dropper_length_tolerance = 0.01;
  const std::vector<double> x = dropper_deviations(p, 2000);
  const auto [mean, std] = mean_and_std(x);
  const double expected_std = 0.01 / std::sqrt(3.);
  EXPECT_NEAR(mean, 0., 4. * expected_std / std::sqrt(x.size()));
  EXPECT_NEAR(std / expected_std, 1., 4. * std::sqrt(0.8 / (4. * x.size())));
  // The tolerance is a hard bound of the uniform draws.
  for (const double d : x)
    ASSERT_LE(std::abs(d), 0.01);
}

TEST(MonteCarlo, NormalDeviationsHaveStdOneThirdOfTheTolerance)
{
  // Normal, 3 sigma = 10 mm: sigma = 3.333 mm. Mean within 4 sigma / sqrt(n),
  // std within 4 x 1/sqrt(2n) relative = 0.67 % for n = 180 000.
  SweepParameters p;
  p.dropper_length_tolerance = 0.01;
  p.distribution = DeviationDistribution::normal;
  const std::vector<double> x = dropper_deviations(p, 2000);
  const auto [mean, std] = mean_and_std(x);
  EXPECT_NEAR(mean, 0., 4. * (0.01 / 3.) / std::sqrt(x.size()));
  EXPECT_NEAR(std / (0.01 / 3.), 1., 4. / std::sqrt(2. * x.size()));
}

TEST(MonteCarlo, ASampleDependsOnlyOnTheSeedAndItsIndex)
{
  SweepParameters p;
  p.seed = 42;
  p.dropper_length_tolerance = 0.01;
  p.steady_arm_height_tolerance = 0.02;
  // The same seed and index: bit for bit the same sample (the rank that runs
  // it and the order of the runs do not enter).
  const InstallationDeviations a = sample_deviations(p, 90, 9, 7);
  sample_deviations(p, 90, 9, 3); // another sample drawn in between changes nothing
  const InstallationDeviations b = sample_deviations(p, 90, 9, 7);
  EXPECT_EQ(a.dropper_lengths, b.dropper_lengths);
  EXPECT_EQ(a.steady_arm_heights, b.steady_arm_heights);
  // A tension tolerance does not shift the other draws: they come first.
  p.tension_tolerance = 0.02;
  const InstallationDeviations c = sample_deviations(p, 90, 9, 7);
  EXPECT_EQ(a.dropper_lengths, c.dropper_lengths);
  EXPECT_EQ(a.steady_arm_heights, c.steady_arm_heights);
  EXPECT_EQ(a.carrier_tension_factor, 1.); // zero tolerance: exactly the design
  EXPECT_NE(c.carrier_tension_factor, 1.);
  // Another seed, another sample.
  p.seed = 43;
  EXPECT_NE(sample_deviations(p, 90, 9, 7).dropper_lengths, a.dropper_lengths);
}

TEST(InstallationDeviations, ShiftLengthsPreloadsAndTensionsOfTheDesign)
{
  CatenaryParameters c;
  c.n_spans = 3;
  c.span = 20.;
  c.steady_arm_stiffness = 2000.;
  c.dropper_positions = {5.5, 14.5};
  c.dropper_lengths = {0.95, 0.9};
  c.steady_arm_preloads = {10., 20.};
  InstallationDeviations d;
  d.dropper_lengths = {0.01, -0.02};
  d.steady_arm_heights = {0.005, -0.01};
  d.contact_wire_tension_factor = 1.02;
  const double tension = c.contact_wire.tension, carrier = c.carrier.tension;
  d.apply(c);
  // Exact arithmetic on the data: 1e-15 allows the last bit only.
  EXPECT_NEAR(c.dropper_lengths[0], 0.96, 1e-15);
  EXPECT_NEAR(c.dropper_lengths[1], 0.88, 1e-15);
  // An arm fixed 5 mm higher pulls k delta = 2000 x 0.005 = 10 N more.
  EXPECT_NEAR(c.steady_arm_preloads[0], 20., 1e-12);
  EXPECT_NEAR(c.steady_arm_preloads[1], 0., 1e-12);
  EXPECT_NEAR(c.contact_wire.tension, 1.02 * tension, 1e-9);
  EXPECT_EQ(c.carrier.tension, carrier);
}

TEST(SweepRows, OutcomesSurviveThePackingAndTheCsvToThePrintedDigit)
{
  SweepOutcome o;
  o.wall_seconds = 1.25, o.steps = 4000, o.rank = 1;
  PantographFigures f;
  f.raw = {169.123456789, 40.987654321, 301.5, 35.25, 292.1, 46.1, 0.5, 4000};
  f.has_filtered = true;
  f.filtered = {169.1, 35.5, 270., 60., 275.6, 62.6, 0., 4000};
  f.has_uplift = true;
  f.max_steady_arm_uplift = 0.0544321987;
  o.pantographs = {f};
  const SweepOutcome back = SweepOutcome::unpack(o.pack());
  // Bitwise: the numbers are sent as bytes.
  EXPECT_EQ(back.pantographs[0].raw.std, f.raw.std);
  EXPECT_EQ(back.pantographs[0].max_steady_arm_uplift, f.max_steady_arm_uplift);
  EXPECT_EQ(back.steps, 4000u);
  const std::string csv =
      "speed_kmh,pantograph,mean,std,mean_minus_3std,mean_plus_3std,"
      "max,min,contact_loss_percent,max_support_uplift_m,filtered_mean,"
      "filtered_std,filtered_mean_minus_3std,filtered_mean_plus_3std,"
      "filtered_max,filtered_min,filtered_contact_loss_percent,status,"
      "reason\n" +
      sweep_rows({"320"}, back, 1);
  const SweepTable t = read_sweep_table(csv, 1);
  ASSERT_EQ(t.rows.size(), 1u);
  // 7 significant digits: relative 5e-7 at most.
  EXPECT_NEAR(t.rows[0].values[SweepTable::statistic("std")], 40.987654321, 5e-7 * 41.);
  EXPECT_NEAR(t.rows[0].values[SweepTable::statistic("max_support_uplift_m")],
              0.0544321987, 5e-7 * 0.0545);
  EXPECT_EQ(t.rows[0].status, "completed");
  // A failed run: one row per pantograph with its reason, quoted (commas kept).
  SweepOutcome failed;
  failed.status = SweepOutcome::Status::failed;
  failed.reason =
      "force |lambda| = 9e3 N of contact exceeds Guards/Multiplier bound, at t = 0.1 s";
  const SweepTable ft = read_sweep_table(
      csv.substr(0, csv.find('\n') + 1) + sweep_rows({"400"}, failed, 2), 1);
  ASSERT_EQ(ft.rows.size(), 2u);
  EXPECT_EQ(ft.rows[1].pantograph, 2u);
  EXPECT_EQ(ft.rows[1].status, "failed");
  EXPECT_EQ(ft.rows[1].reason, failed.reason);
  EXPECT_TRUE(std::isnan(ft.rows[1].values[0]));
}

TEST(SweepRows, PercentilesAreLinearBetweenOrderStatistics)
{
  // Positions p/100 (n - 1) in {1, 2, 3, 4, 5}: exact in binary up to 1e-12.
  const std::vector<double> x = {1., 2., 3., 4., 5.};
  EXPECT_NEAR(percentile(x, 50.), 3., 1e-12);
  EXPECT_NEAR(percentile(x, 5.), 1.2, 1e-12);
  EXPECT_NEAR(percentile(x, 95.), 4.8, 1e-12);
  EXPECT_NEAR(percentile(x, 100.), 5., 1e-12);
}

TEST(SweepRun, EqualsTheSingleRunOfTheSameCaseExactly)
{
  // The sweep runs the case through the CaseRunner with the same observer
  // as a dynamic run: the same figures bit for bit.
  const SweepCase c = small_case();
  const SweepOutcome o = execute_sweep_run(c, [] {});
  ASSERT_EQ(o.status, SweepOutcome::Status::completed) << o.reason;
  CaseRunner runner(c.case_data);
  ContactStatistics statistics(c.statistics, runner.discretisation(), runner.system());
  runner.run({&statistics});
  ASSERT_EQ(o.pantographs.size(), 1u);
  EXPECT_EQ(o.pantographs[0].raw.std, statistics.result().raw.std);
  EXPECT_EQ(o.pantographs[0].filtered.max, statistics.result().filtered->max);
  EXPECT_EQ(o.steps, runner.number_of_steps());
  // A contact force never pushes: the raw minimum is >= 0 (penalty and rigid
  // unilateral contact alike report lambda_p >= 0 for a lost contact).
  EXPECT_GE(o.pantographs[0].raw.min, 0.);
}

TEST(SweepRun, AStepAboveTheStabilityLimitIsARefusedRunWithItsReason)
{
  SweepCase c = small_case();
  c.case_data.time_integration.time_step = 1e-3;
  const SweepOutcome o = execute_sweep_run(c, [] {});
  EXPECT_EQ(o.status, SweepOutcome::Status::refused);
  EXPECT_NE(
      o.reason.find("Time integration/Time step = 0.001: above the stability limit"),
      std::string::npos)
      << o.reason;
}
