// Sweeps: the value lists and ranges of subsection Sweep and their refusals
// (duplicate values), the Monte Carlo deviations (distribution,
// reproducibility), the installed catenary and its refusal, the rows of a
// sweep's CSV and their transfer between MPI ranks, the percentiles of a
// Monte Carlo distribution, a sweep's run against the single run of the same
// case, and what a resume accepts from a partial file and what it refuses.
#include <pantocat/app/program_parameters.h>
#include <pantocat/base/number_format.h>
#include <pantocat/simulation/case_runner.h>
#include <pantocat/simulation/contact_statistics.h>
#include <pantocat/studies/sweep_partial.h>
#include <pantocat/studies/sweep_plots.h>
#include <pantocat/studies/sweep_run.h>
#include <pantocat/studies/sweep_study.h>

#include <support/input_errors.h>

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <regex>

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

/// The refusal of subsection Sweep with @p entries set, for run mode @p mode ("" if
/// none).
std::string sweep_refusal(const std::string& mode,
                          const std::vector<std::pair<std::string, std::string>>& entries)
{
  dealii::ParameterHandler prm;
  SweepParameters::declare_parameters(prm);
  prm.enter_subsection("Sweep");
  for (const auto& [name, value] : entries)
    prm.set(name, value);
  prm.leave_subsection();
  SweepParameters s;
  return input_error_of([&] { s.parse_parameters(prm, mode); });
}

const std::string partial_name = "out/speed_sweep.csv.partial";

/// A speed sweep of three speeds with two pantographs, as a partial file knows it.
SweepPlan two_pantograph_plan()
{
  SweepPlan plan;
  plan.key_columns = {"speed_kmh"};
  plan.keys = {{"90"}, {"115.2"}, {"144"}};
  plan.costs = {3., 2., 1.};
  plan.pantographs = {2, 2, 2};
  plan.parameters = {{"Catenary/Contact wire/Tension", "20000"},
                     {"Scene/Number of pantographs", "2"},
                     {"Sweep/Speeds", "90, 115.2, 144"}};
  return plan;
}

/// The two rows of run @p k of two_pantograph_plan(), completed with figures.
std::string completed_rows(const SweepPlan& plan, const unsigned int k)
{
  SweepOutcome o;
  for (unsigned int p = 1; p <= 2; ++p)
  {
    PantographFigures f;
    f.number = p;
    f.raw = {150. + k, 30.25 + p, 250.5, 40.125, 241.75, 59.25, 0., 2000};
    f.has_filtered = true;
    f.filtered = {150. + k, 20.5 + p, 210., 90., 211.5, 88.5, 0., 2000};
    o.pantographs.push_back(f);
  }
  return sweep_rows(plan.keys[k], o, 2);
}

/// The partial file of two_pantograph_plan() after runs 0 and 2 (a stop).
std::string stopped_partial(const SweepPlan& plan)
{
  return partial_file_start(plan) + partial_record(completed_rows(plan, 0)) +
         partial_record(completed_rows(plan, 2));
}

/// Line number of the first row of the partial file of @p plan (after the header).
unsigned int first_row_line(const SweepPlan& plan)
{
  return plan.parameters.size() + 3;
}

/// The refusal of a resume from @p text ("" if none).
std::string resume_refusal(const std::string& text, const SweepPlan& plan)
{
  return input_error_of([&] { read_partial_file(text, partial_name, plan); });
}

/// @p text with its line @p line (1-based) replaced by @p lines ("" removes it).
std::string with_line(const std::string& text, const unsigned int line,
                      const std::string& lines)
{
  std::size_t begin = 0;
  for (unsigned int i = 1; i < line; ++i)
    begin = text.find('\n', begin) + 1;
  const std::size_t end = text.find('\n', begin) + 1;
  return text.substr(0, begin) + lines + text.substr(end);
}

/// Line @p line (1-based) of @p text without its newline.
std::string line_of(const std::string& text, const unsigned int line)
{
  std::size_t begin = 0;
  for (unsigned int i = 1; i < line; ++i)
    begin = text.find('\n', begin) + 1;
  return text.substr(begin, text.find('\n', begin) - begin);
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

TEST(SweepValues, ValuesThatAreTheSameRunAreRefusedNamingTheValue)
{
  // 250, 250.0 and 2.5e2 are one number: three runs of the same case.
  EXPECT_EQ(sweep_refusal("speed sweep", {{"Speeds", "250, 250.0, 2.5e2"}}),
            "Sweep/Speeds = 250, 250.0, 2.5e2: the value 250 is given 3 times (as 250, "
            "250.0, 2.5e2), which would run the same case again; allowed: each value "
            "once");
  // Speeds that differ below the 12 digits of speed_kmh would be rows with the same key.
  EXPECT_EQ(
      sweep_refusal("speed sweep", {{"Speeds", "100 to 100.000000000001 step 4e-13"}}),
      "Sweep/Speeds = 100 to 100.000000000001 step 4e-13: the value 100 is given 3 "
      "times (as 100, 100, 100), which would run the same case again; allowed: each "
      "value once");
  EXPECT_EQ(sweep_refusal("speed sweep", {{"Speeds", "250, 250.1"}}), "");
  // A parameter sweep: the values as the prm entry reads them (2e4 = 20000).
  EXPECT_EQ(
      sweep_refusal("parameter sweep", {{"Parameter", "Catenary/Contact wire/Tension"},
                                        {"Values", "2e4, 21000, 20000"}}),
      "Sweep/Values = 2e4, 21000, 20000: the value 2e4 is given 2 times (as 2e4, "
      "20000), which would run the same case again; allowed: each value once");
  EXPECT_NE(sweep_refusal("parameter sweep",
                          {{"Parameter", "Catenary/Contact wire/Tension"},
                           {"Values", "2e4, 21000"},
                           {"Second parameter", "Catenary/Messenger/Tension"},
                           {"Second values", "1.6e4 to 1.8e4 step 1e3, 17000"}})
                .find("Sweep/Second values = 1.6e4 to 1.8e4 step 1e3, 17000: "),
            std::string::npos);
  EXPECT_EQ(
      sweep_refusal("parameter sweep", {{"Parameter", "Catenary/Contact wire/Tension"},
                                        {"Values", "2e4, 21000"}}),
      "");
}

TEST(MonteCarlo, ASampleWithADropperOfLengthZeroOrLessIsARefusedRunWithItsReason)
{
  // The paper's droppers are 0.95 m long; a deviation of -0.96 m installs one
  // of -0.01 m, which Catenary/Droppers/Lengths refuses in a prm file: the
  // same check refuses the sample, which then has no figures.
  SweepCase c = small_case();
  c.case_data.installation.dropper_lengths = {-0.96, 0.};
  const SweepOutcome o = execute_sweep_run(c, [] {});
  EXPECT_EQ(o.status, SweepOutcome::Status::refused);
  EXPECT_EQ(o.reason, "the catenary as installed (with its installation deviations) is "
                      "refused: Catenary/Droppers/Lengths = -0.01: must be > 0");
  EXPECT_TRUE(o.pantographs.empty());
  // -0.94 m leaves 1 cm: the sample runs (and keeps contact: raw min >= 0).
  c.case_data.installation.dropper_lengths = {-0.94, 0.};
  const SweepOutcome short_dropper = execute_sweep_run(c, [] {});
  EXPECT_EQ(short_dropper.status, SweepOutcome::Status::completed)
      << short_dropper.reason;
}

TEST(SweepPartial, FinishedRunsAreReadBackByteForByte)
{
  const SweepPlan plan = two_pantograph_plan();
  const PartialRuns r = read_partial_file(stopped_partial(plan), partial_name, plan);
  ASSERT_EQ(r.rows.size(), 2u);
  EXPECT_EQ(r.rows.at(0), completed_rows(plan, 0));
  EXPECT_EQ(r.rows.at(2), completed_rows(plan, 2));
  EXPECT_EQ(r.dropped_lines, 0u);
  // The file says who wrote it, with which parameters, then the CSV header.
  const std::string text = stopped_partial(plan);
  EXPECT_EQ(line_of(text, 1), "# pantocat-fem " + program_version() +
                                  ": partial results of a sweep (Sweep/Resume = true "
                                  "goes on from here)");
  EXPECT_EQ(line_of(text, 2), "# set Catenary/Contact wire/Tension = 20000");
  EXPECT_EQ(line_of(text, first_row_line(plan) - 1) + "\n",
            sweep_csv_header(plan.key_columns));
  // A failed run: one row per pantograph without figures, with its reason.
  SweepOutcome failed;
  failed.status = SweepOutcome::Status::failed;
  failed.reason = "unstable: a displacement of 30 m exceeds the span 20 m, at t = 0.1 s";
  const std::string failed_rows = sweep_rows(plan.keys[1], failed, 2);
  EXPECT_EQ(read_partial_file(text + partial_record(failed_rows), partial_name, plan)
                .rows.at(1),
            failed_rows);
}

TEST(SweepPartial, ARunCutShortByAStopRunsAgain)
{
  // What a kill during the append of run 1 leaves: its first row, and the
  // second cut short or whole but without the end line, or the end line cut.
  const SweepPlan plan = two_pantograph_plan();
  const std::string rows = completed_rows(plan, 1);
  const std::string first_row = rows.substr(0, rows.find('\n') + 1);
  const std::string record = partial_record(rows);
  for (const auto& [tail, dropped] : std::vector<std::pair<std::string, unsigned int>>{
           {first_row + rows.substr(first_row.size(), 25), 2},
           {rows, 2},
           {record.substr(0, record.size() - 1), 3}, // the end line without its newline
           {first_row.substr(0, 10), 1}})
  {
    const PartialRuns r =
        read_partial_file(stopped_partial(plan) + tail, partial_name, plan);
    EXPECT_EQ(r.rows.size(), 2u) << tail;
    EXPECT_EQ(r.rows.count(1), 0u) << tail; // run 1 runs again
    EXPECT_EQ(r.dropped_lines, dropped) << tail;
  }
}

TEST(SweepPartial, APartialFileOfOtherParametersOrAnotherVersionIsRefused)
{
  const SweepPlan plan = two_pantograph_plan();
  const std::string text = stopped_partial(plan);
  const std::string allowed =
      "; allowed: the partial file of this sweep as a stopped run left it, or remove it "
      "(Resume = false starts the sweep afresh and replaces it), or another output "
      "directory";
  SweepPlan other = plan;
  other.parameters[0].second = "22000";
  EXPECT_EQ(resume_refusal(text, other),
            "Sweep/Resume = true: " + partial_name +
                ": written by a sweep with other parameters: Catenary/Contact "
                "wire/Tension = 20000 there, 22000 in this sweep" +
                allowed);
  other.parameters.emplace_back("Catenary/Span", "30");
  EXPECT_NE(
      resume_refusal(text, other).find("22000 in this sweep (and 1 more entry differs)"),
      std::string::npos);
  other = plan;
  other.parameters.pop_back();
  EXPECT_NE(
      resume_refusal(text, other)
          .find("Sweep/Speeds = 90, 115.2, 144 there, which this sweep does not have"),
      std::string::npos);
  // Another version: its rows may differ.
  const std::string old_version =
      std::regex_replace(text, std::regex("pantocat-fem [^:]*:"),
                         "pantocat-fem 0.0.1:", std::regex_constants::format_first_only);
  EXPECT_EQ(resume_refusal(old_version, plan),
            "Sweep/Resume = true: " + partial_name +
                ": written by pantocat-fem 0.0.1, this is " + program_version() +
                ", whose rows may differ" + allowed);
  // No version line (the CSV's header first): not a partial file of this program.
  EXPECT_NE(resume_refusal(text.substr(text.find("speed_kmh,")), plan)
                .find(": not a partial file of pantocat-fem " + program_version()),
            std::string::npos);
  // Another sweep's columns.
  SweepPlan parameter_sweep = plan;
  parameter_sweep.key_columns = {"Catenary/Contact wire/Tension"};
  EXPECT_NE(resume_refusal(text, parameter_sweep)
                .find(", line " + std::to_string(first_row_line(plan) - 1) +
                      ": not the columns of this sweep"),
            std::string::npos);
}

TEST(SweepPartial, DamagedRowsAreRefusedNamingTheFileAndTheLine)
{
  const SweepPlan plan = two_pantograph_plan();
  const std::string text = stopped_partial(plan);
  const unsigned int row = first_row_line(plan); // pantograph 1 of run 0
  const std::string first = line_of(text, row);
  const std::string end = line_of(text, row + 2);
  const auto damaged = [&](const std::string& replacement)
  { return resume_refusal(with_line(text, row, replacement), plan); };
  const auto at = [&](const unsigned int line, const std::string& what)
  {
    return "Sweep/Resume = true: " + partial_name + ", line " + std::to_string(line) +
           ": " + what;
  };
  const auto starts = [](const std::string& message, const std::string& start)
  { return message.rfind(start, 0) == 0 ? start : message; };

  std::string m = damaged("#!%garbage\n");
  EXPECT_EQ(starts(m, at(row, "1 field, a row has 19")),
            at(row, "1 field, a row has 19"));
  // Too few fields: the row cut after its 17th field, with its newline.
  std::size_t cut = 0;
  for (int i = 0; i < 17; ++i)
    cut = first.find(',', cut) + 1;
  m = damaged(first.substr(0, cut - 1) + "\n");
  EXPECT_EQ(starts(m, at(row, "17 fields, a row has 19")),
            at(row, "17 fields, a row has 19"));
  // nan where a figure must be finite (std is the fourth field).
  const std::string std_field = "," + csv_field(31.25) + ",";
  ASSERT_NE(first.find(std_field), std::string::npos);
  m = damaged(std::regex_replace(first, std::regex(std_field), ",nan,") + "\n");
  EXPECT_EQ(starts(m, at(row, "std = \"nan\" is not a finite number")),
            at(row, "std = \"nan\" is not a finite number"));
  m = damaged(std::regex_replace(first, std::regex("completed"), "bogus") + "\n");
  EXPECT_EQ(starts(m, at(row, "status \"bogus\" is not completed, failed or refused")),
            at(row, "status \"bogus\" is not completed, failed or refused"));
  // A figure changed that still parses: the end line's CRC-32 finds it.
  m = damaged(std::regex_replace(first, std::regex(std_field), ",31.26,") + "\n");
  EXPECT_EQ(starts(m, at(row + 2, "the end line does not match the 2 rows above it")),
            at(row + 2, "the end line does not match the 2 rows above it"));
  // A row twice, and a run twice.
  m = damaged(first + "\n" + first + "\n");
  EXPECT_EQ(starts(m, at(row + 1, "pantograph 1 after pantograph 1")),
            at(row + 1, "pantograph 1 after pantograph 1"));
  m = resume_refusal(text + partial_record(completed_rows(plan, 0)), plan);
  EXPECT_EQ(starts(m, at(row + 6, "a second record of the run speed_kmh = 90 (its first "
                                  "ends on line " +
                                      std::to_string(row + 2) + ")")),
            at(row + 6, "a second record of the run speed_kmh = 90 (its first ends on "
                        "line " +
                            std::to_string(row + 2) + ")"));
  // A run this sweep does not have, a failed run with figures, an end line alone.
  m = damaged(std::regex_replace(first, std::regex("^90,"), "95,") + "\n");
  EXPECT_EQ(starts(m, at(row, "a run (speed_kmh = 95) that this sweep does not have")),
            at(row, "a run (speed_kmh = 95) that this sweep does not have"));
  m = damaged(std::regex_replace(first, std::regex("completed,\"\""), "failed,\"x\"") +
              "\n");
  EXPECT_EQ(starts(m, at(row, "mean = 150 in a run that failed")),
            at(row, "mean = 150 in a run that failed"));
  m = resume_refusal(with_line(with_line(text, row, ""), row, ""), plan);
  EXPECT_EQ(starts(m, at(row, "an end line without the rows of a run")),
            at(row, "an end line without the rows of a run"));
  // A whole garbage line at the end is no cut row: a stop leaves no such line.
  m = resume_refusal(text + "garbage\n", plan);
  EXPECT_EQ(starts(m, at(row + 6, "1 field, a row has 19")),
            at(row + 6, "1 field, a row has 19"));
  // Only the last run's end line may be missing: a row of another run after it.
  m = resume_refusal(
      text + completed_rows(plan, 1).substr(0, completed_rows(plan, 1).find('\n') + 1) +
          completed_rows(plan, 0),
      plan);
  EXPECT_NE(m.find("a row of the run speed_kmh = 90 inside the record of the run "
                   "speed_kmh = 115.2, whose end line is missing"),
            std::string::npos)
      << m;
  EXPECT_NE(end.find("# end of run: 2 rows, CRC-32 "), std::string::npos);
}
