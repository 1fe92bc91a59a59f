// The evaluation of a run as railway engineers read it (issue 15,
// doc/evaluation.md): the contact-force statistics raw and after the
// zero-phase Butterworth low pass in a window given by span numbers, the
// contact-loss share, the uplift at the steady arms, the dropper slack
// events, the refusals of bad windows and the plot over x.
#include <pantocat/analysis/butterworth_low_pass.h>
#include <pantocat/app/run_modes.h>
#include <pantocat/base/input_error.h>
#include <pantocat/io/plots.h>
#include <pantocat/scene/steady_arms.h>
#include <pantocat/simulation/case_runner.h>
#include <pantocat/simulation/contact_statistics.h>
#include <pantocat/simulation/run_statistics.h>

#include "support/case_files.h"
#include "support/input_errors.h"

#include <deal.II/base/utilities.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace pantocat;

namespace
{
constexpr double fs = 2000.; // sample rate [Hz] of the synthetic series
constexpr double fc = 20.;   // cut-off [Hz]

/// The supports of S55: 10 spans of 55 m.
std::vector<double> s55_supports()
{
  std::vector<double> x;
  for (unsigned int k = 0; k <= 10; ++k)
    x.push_back(55. * k);
  return x;
}

/// A series at 2 kHz of @p n points with x_p = @p speed t and lambda_p = @p force(t).
template <typename Force>
ContactForceSeries series_of(const std::size_t n, const double speed, const Force& force)
{
  ContactForceSeries s;
  for (std::size_t k = 0; k < n; ++k)
  {
    s.t.push_back(k / fs);
    s.x_p.push_back(speed * s.t.back());
    s.lambda_p.push_back(force(s.t.back()));
    s.in_contact.push_back(true);
  }
  return s;
}

/// Amplitude of the component at @p f over the points with x_p in @p w (whole periods).
double amplitude_in(const ContactForceSeries& s, const std::vector<double>& y,
                    const double f, const EvaluationWindow& w)
{
  double sine = 0., cosine = 0.;
  std::size_t count = 0;
  for (std::size_t k = 0; k < y.size(); ++k)
    if (w.contains(s.x_p[k]) && s.x_p[k] < w.end) // [start, end): whole periods
    {
      sine += y[k] * std::sin(2. * M_PI * f * s.t[k]);
      cosine += y[k] * std::cos(2. * M_PI * f * s.t[k]);
      ++count;
    }
  return 2. * std::hypot(sine, cosine) / count;
}

} // namespace

// ---------------------------------------------------------------- windows
// Span numbers 1-based: spans first..last are the pantograph between the
// support before span first and the support after span last (exact: the
// supports are sums of the span lengths).
TEST(EvaluationWindow, SpansGiveTheSupportsAroundThem)
{
  StatisticsParameters p;
  p.window_spans = {5, 6};
  const EvaluationWindow w = p.evaluation_window(s55_supports());
  EXPECT_EQ(w.start, 220.);
  EXPECT_EQ(w.end, 330.);
  EXPECT_TRUE(w.given_by_spans());
  EXPECT_EQ(w.describe(), "x_p in [220, 330] m (spans 5-6)");
  const std::vector<std::pair<std::vector<long>, std::pair<double, double>>> cases{
      {{1}, {0., 55.}}, {{10, 10}, {495., 550.}}, {{1, 10}, {0., 550.}}};
  for (const auto& [spans, expected] : cases)
  {
    p.window_spans = spans;
    const EvaluationWindow v = p.evaluation_window(s55_supports());
    EXPECT_EQ(v.start, expected.first);
    EXPECT_EQ(v.end, expected.second);
  }
  // Spans of different lengths (20, 30, 25 m): spans 2-3 = [20, 75] m.
  p.window_spans = {2, 3};
  const EvaluationWindow uneven = p.evaluation_window({0., 20., 50., 75.});
  EXPECT_EQ(uneven.start, 20.);
  EXPECT_EQ(uneven.end, 75.);
  // In metres, or neither: the whole run.
  p.window_spans.clear();
  p.window = {100., 200.};
  EXPECT_FALSE(p.evaluation_window(s55_supports()).given_by_spans());
  EXPECT_EQ(p.evaluation_window(s55_supports()).describe(), "x_p in [100, 200] m");
  p.window.clear();
  EXPECT_TRUE(p.evaluation_window(s55_supports()).whole_run());
}

// Each refusal is one line: the parameter, the value as given, what is allowed.
TEST(EvaluationWindow, BadWindowsAreRefusedNamingParameterValueAndRange)
{
  const auto refusal =
      [](const std::vector<long>& spans, const std::vector<double>& metres)
  {
    StatisticsParameters p;
    p.window_spans = spans;
    p.window = metres;
    // S55 at dt = 1e-4 s, the pantograph from 0 to 550 m.
    return input_error_of([&] { p.check(1e-4, 0., 550., s55_supports()); });
  };
  EXPECT_EQ(refusal({0, 6}, {}),
            "Statistics/Window spans = 0, 6: span numbers run from 1 "
            "to 10 (the section has 10 spans)");
  EXPECT_EQ(refusal({5, 11}, {}),
            "Statistics/Window spans = 5, 11: span numbers run from "
            "1 to 10 (the section has 10 spans)");
  EXPECT_EQ(refusal({6, 5}, {}), "Statistics/Window spans = 6, 5: first, last with first "
                                 "<= last (1 <= first <= last <= 10)");
  EXPECT_EQ(refusal({4, 5, 6}, {}), "Statistics/Window spans = 4, 5, 6: one span number, "
                                    "or two: the first and the last span of the window");
  EXPECT_EQ(refusal({5, 6}, {220., 330.}),
            "Statistics/Window spans = 5, 6: not together with Statistics/Window = 220, "
            "330: give the evaluation window either by span numbers or in metres");
  EXPECT_EQ(refusal({}, {-10., 100.}),
            "Statistics/Window = -10, 100: must lie inside the "
            "section, from x = 0 to 550 m");
  EXPECT_EQ(refusal({}, {500., 560.}),
            "Statistics/Window = 500, 560: must lie inside the "
            "section, from x = 0 to 550 m");
  // Within the section but not on the run (the pantograph from 0 to 100 m).
  StatisticsParameters p;
  p.window_spans = {5, 6};
  EXPECT_EQ(
      input_error_of([&] { p.check(1e-4, 0., 100., s55_supports()); }),
      "Statistics/Window spans = 5, 6: the window x = 220 to 330 m must overlap the "
      "run from x_p = 0 to 100 m (or be empty: the whole run)");
  // What is allowed passes.
  EXPECT_EQ(refusal({5, 6}, {}), "");
  EXPECT_EQ(refusal({7}, {}), "");
  EXPECT_EQ(refusal({}, {220., 330.}), "");
}

// ---------------------------------------------------------------- statistics
// lambda_p = 169 + 20 sin(2 pi 5 t) + 8 sin(2 pi 60 t), 6 s at 2 kHz, x_p =
// 110 t: spans 5-6 are t in [2, 3] s, 2001 points holding whole periods of
// both components plus one point (t = 3 s) where both vanish. Hence, exactly:
// mean 169 N and std = sqrt((A_5^2 + A_60^2)/2 * 2000/2001) with A_5 = 20 N,
// A_60 = 8 N raw, and A_f = A |H(f)|^2 after the 20 Hz low pass of order 4
// forwards and backwards: |H(5 Hz)|^2 = 1 - 1.5e-5 (the 5 Hz sine is kept),
// |H(60 Hz)|^2 = 1.5e-4 (-76 dB). The window lies 2 s from the record's ends,
// where the filter's start-up transient (decay 48/s) is below e^-96, so the
// filtered figures agree with the analytic ones to round-off: 1e-9 relative
// asserted (1e-6 for the 60 Hz amplitude, itself 1.2e-3 N).
TEST(ContactForceStatistics, LowPassKeepsTheMeanAnd5HzAndTakesOutTheAnalytic60HzShare)
{
  const auto s = series_of(12001, 110.,
                           [](const double t)
                           {
                             return 169. + 20. * std::sin(2. * M_PI * 5. * t) +
                                    8. * std::sin(2. * M_PI * 60. * t);
                           });
  StatisticsParameters p;
  p.low_pass_cutoff = fc;
  p.window_spans = {5, 6};
  const EvaluationWindow w = p.evaluation_window(s55_supports());
  std::vector<double> filtered;
  const ContactForceStatistics r = evaluate_contact_force(s, p, w, &filtered);
  const ButterworthLowPass filter(fc, fs, 4);
  const double g5 = std::pow(filter.gain(5.), 2), g60 = std::pow(filter.gain(60.), 2);
  EXPECT_NEAR(1. - g5, 1.5e-5, 0.1e-5);
  EXPECT_NEAR(g60, 1.5e-4, 0.1e-4);

  EXPECT_EQ(r.raw.n_points, 2001u);
  const double share = 2000. / 2001.;
  EXPECT_NEAR(r.raw.mean, 169., 1e-12 * 169.);
  const double raw_std = std::sqrt((20. * 20. + 8. * 8.) / 2. * share);
  EXPECT_NEAR(r.raw.std, raw_std, 1e-12 * raw_std);
  EXPECT_NEAR(r.raw.mean_plus_3std, r.raw.mean + 3. * r.raw.std, 1e-12);
  EXPECT_NEAR(r.raw.mean_minus_3std, r.raw.mean - 3. * r.raw.std, 1e-12);
  EXPECT_EQ(r.raw.contact_loss_percent, 0.);

  ASSERT_TRUE(r.filtered.has_value());
  EXPECT_EQ(r.filtered->n_points, 2001u);
  EXPECT_NEAR(r.filtered->mean, 169., 1e-9 * 169.);
  const double filtered_std =
      std::sqrt((std::pow(20. * g5, 2) + std::pow(8. * g60, 2)) / 2. * share);
  EXPECT_NEAR(r.filtered->std, filtered_std, 1e-9 * filtered_std);
  // The 5 Hz peaks fall on samples (t = 0.05 + 0.2 k s), where the 60 Hz sine
  // vanishes: max and min are 169 +/- 20 |H(5 Hz)|^2.
  EXPECT_NEAR(r.filtered->max, 169. + 20. * g5, 1e-9 * 169.);
  EXPECT_NEAR(r.filtered->min, 169. - 20. * g5, 1e-9 * 169.);
  EXPECT_NEAR(amplitude_in(s, filtered, 5., w), 20. * g5, 1e-9 * 20.);
  EXPECT_NEAR(amplitude_in(s, filtered, 60., w) / (8. * g60), 1., 1e-6);
  EXPECT_EQ(r.filter_cutoff_hz, fc);
  EXPECT_EQ(r.filter_order, 4u);
}

// Contact loss is the share of the window's time points with force <= 0,
// whatever the constraint's flag says: 1000 points, lambda_p = 100 N but 0 at
// points 300..399 (contact lost) and -3 N at 500..519 (a multiplier below
// zero), the flag "in contact" set everywhere: 120 of 1000 = 12 %; in the
// window x_p in [62.5, 112.5] m (points 250..450): 100 of 201.
TEST(ContactForceStatistics, ContactLossIsTheShareOfPointsWithForceAtMostZero)
{
  ContactForceSeries s;
  for (unsigned int k = 0; k < 1000; ++k)
  {
    s.t.push_back(1e-3 * k);
    s.x_p.push_back(0.25 * k);
    s.lambda_p.push_back(k >= 300 && k < 400 ? 0. : (k >= 500 && k < 520 ? -3. : 100.));
    s.in_contact.push_back(true);
  }
  const StatisticsParameters p;
  EXPECT_NEAR(evaluate_contact_force(s, p, {}).raw.contact_loss_percent, 12., 1e-12);
  const ForceFigures in_window = evaluate_contact_force(s, p, {62.5, 112.5}).raw;
  EXPECT_EQ(in_window.n_points, 201u);
  EXPECT_NEAR(in_window.contact_loss_percent, 100. * 100. / 201., 1e-12);
}

// The filtered share uses the filtered force: lambda_p = -50 + 100 sin(2 pi t)
// + 30 sin(2 pi 60 t), 4 s (8000 points, 4 periods). The low pass leaves the
// 1 Hz part (1 - |H|^2 = 4e-11) and 30 |H(60 Hz)|^2 = 4.6 mN of the ripple;
// the clean part is <= 0 where sin <= 1/2: 2000 - 667 of every 2000 points
// (the samples nearest the crossings are 0.09 N away from 0, far more than the
// ripple left), so exactly 66.65 %. The raw share lies between those of the
// clean part <= -30 N and <= 30 N: 50 + 100 asin(0.2)/pi and 50 + 100
// asin(0.8)/pi percent (to the resolution 8 crossings / 8000 points = 0.1 %).
TEST(ContactForceStatistics, FilteredContactLossCountsTheFilteredForce)
{
  const auto s = series_of(8000, 10.,
                           [](const double t) {
                             return -50. + 100. * std::sin(2. * M_PI * t) +
                                    30. * std::sin(2. * M_PI * 60. * t);
                           });
  StatisticsParameters p;
  p.low_pass_cutoff = fc;
  const ContactForceStatistics r = evaluate_contact_force(s, p, {});
  ASSERT_TRUE(r.filtered.has_value());
  EXPECT_NEAR(r.filtered->contact_loss_percent, 100. * 4. * 1333. / 8000., 1e-9);
  EXPECT_GE(r.raw.contact_loss_percent, 50. + 100. * std::asin(0.2) / M_PI - 0.1);
  EXPECT_LE(r.raw.contact_loss_percent, 50. + 100. * std::asin(0.8) / M_PI + 0.1);
}

// ---------------------------------------------------------------- droppers
// Slack intervals begin at the first time point a dropper is inactive. Time
// points t = 0..5 s: dropper 1 slack at t = 1 and at t = 3, taut in between
// and after (two intervals), dropper 2 slack from t = 4 to the end (one
// interval, closed at the end of the run).
TEST(RunStatistics, DropperSlackEventsCountTheIntervalsThatBeginInTheWindow)
{
  SimulationLayout layout;
  layout.constraint_names = {"dropper 1", "dropper 2"};
  layout.dropper_indices = {0, 1};
  RunStatistics run;
  run.start(layout);
  const bool taut1[] = {true, false, true, false, true, true};
  const bool taut2[] = {true, true, true, true, false, false};
  for (unsigned int k = 0; k < 6; ++k)
  {
    TimePoint point;
    point.t = k;
    point.lambda = {0., 0.};
    point.active = {taut1[k], taut2[k]};
    run.observe(point);
  }
  run.finish();
  const DropperSlackEvents all = run.dropper_slack_events();
  EXPECT_EQ(all.per_dropper, (std::vector<unsigned long>{2, 1}));
  EXPECT_EQ(all.total, 3u);
  // Beginning in [2, 4] s: dropper 1 at t = 3, dropper 2 at t = 4 (ends included).
  const DropperSlackEvents window = run.dropper_slack_events(2., 4.);
  EXPECT_EQ(window.per_dropper, (std::vector<unsigned long>{1, 1}));
  EXPECT_EQ(window.total, 2u);
}

// ---------------------------------------------------------------- a section
namespace
{
/**
 * Three spans of F3 (65 m) with steady arms (2673.58 N/m, 1 kg) at 65 and
 * 130 m, designed droppers; the paper's pantograph at 32 m/s from 60 to 70 m
 * (past the steady arm at 65 m); FDM N+1 = 1170 (h = 1/6 m, which resolves the
 * load), BDF-2 with dt = 5e-4 s (625 steps).
 */
ProgramParameters three_spans(const std::vector<std::string>& extra = {})
{
  std::vector<std::string> overrides{"Catenary/Number of spans=3",
                                     "Catenary/Supports/Steady arm stiffness=2673.58",
                                     "Catenary/Supports/Steady arm mass=1",
                                     "Discretisation/Number of intervals=1170",
                                     "Time integration/Integrator=bdf2",
                                     "Time integration/Time step=5e-4",
                                     "Pantograph/Initial position=60",
                                     "Pantograph/Final position=70"};
  overrides.insert(overrides.end(), extra.begin(), extra.end());
  return read_case(source_file("prm/catenary/paper-fig3.prm"), overrides);
}

std::string text_of(const std::string& file)
{
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// max_t w(t) - w(0) of the column @p name of time_series.csv.
double largest_rise(const std::string& csv, const std::string& name)
{
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  const auto header = dealii::Utilities::split_string_list(line, ',');
  const std::size_t c = std::find(header.begin(), header.end(), name) - header.begin();
  EXPECT_LT(c, header.size()) << name << " not in " << line;
  double first = std::nan(""), largest = -1.;
  while (std::getline(in, line))
  {
    const double w = std::stod(dealii::Utilities::split_string_list(line, ',').at(c));
    if (std::isnan(first))
      first = w;
    largest = std::max(largest, w - first);
  }
  return largest;
}
} // namespace

// The steady arms counted are those in the window, ends included; their
// uplift is the largest rise of the contact wire there over the whole run,
// the same as the probes of the run show (1e-15 m: the same rows). Windows:
// spans 1-2 = [0, 130] m (both arms, 130 m at the end), span 2 = [65, 130]
// m (both, at its ends), [66, 129] m (none: no figure).
TEST(SteadyArmUplift, IsTheLargestRiseOfTheWireAtTheArmsInTheWindow)
{
  const ProgramParameters p = three_spans();
  CaseRunner runner(p.make_case(), {{65., 130.}, false});
  const std::vector<double> arms =
      SteadyArms::positions(runner.case_data().scene, runner.case_data().catenary);
  ASSERT_EQ(arms, (std::vector<double>{65., 130.}));
  StatisticsParameters spans12 = p.statistics, span2 = p.statistics, none = p.statistics;
  spans12.window_spans = {1, 2};
  span2.window_spans = {2};
  none.window = {66., 129.};
  std::vector<ContactStatistics> observers;
  for (const StatisticsParameters* s : {&spans12, &span2, &none})
    observers.emplace_back(*s, runner.discretisation(), runner.system(), arms);
  struct Probes : SimulationObserver
  {
    std::vector<std::vector<double>> w;
    void observe(const TimePoint& point) override { w.push_back(point.probes); }
  } probes;
  runner.run({&observers[0], &observers[1], &observers[2], &probes});
  std::vector<double> rise(2, -1.);
  for (const auto& w : probes.w)
    for (unsigned int k = 0; k < 2; ++k)
      rise[k] = std::max(rise[k], w[k] - probes.w.front()[k]);
  for (unsigned int o = 0; o < 2; ++o)
  {
    const ContactForceStatistics& r = observers[o].result();
    ASSERT_EQ(r.steady_arms.size(), 2u) << o;
    for (unsigned int k = 0; k < 2; ++k)
    {
      EXPECT_EQ(r.steady_arms[k].x, arms[k]);
      EXPECT_NEAR(r.steady_arms[k].max_uplift, rise[k], 1e-15);
    }
    EXPECT_EQ(r.max_steady_arm_uplift(), std::max(rise[0], rise[1]));
  }
  EXPECT_TRUE(observers[2].result().steady_arms.empty());
  EXPECT_FALSE(observers[2].result().max_steady_arm_uplift().has_value());
  // The pantograph passes the arm at 65 m and lifts the wire there; the arm
  // at 130 m, 60 m ahead, hardly moves.
  EXPECT_GT(rise[0], 1e-3);
  EXPECT_GT(rise[0], 10. * rise[1]);
}

// summary.json of a run through the program, per pantograph and at the top
// level (the same object): statistics.window, raw and filtered with exactly the
// names scripts read, the steady arms of spans 1-2 with the uplift that
// time_series.csv shows at their probes (1e-11 m: 10 significant digits of
// displacements below 0.1 m), and the dropper slack events matching the
// intervals.
TEST(SteadyArmUplift, SummaryJsonHoldsTheEvaluationUnderTheNamesScriptsRead)
{
  ProgramParameters p =
      three_spans({"Statistics/Window spans=1, 2", "Statistics/Low-pass cut-off=20",
                   "Output/Probe positions=65, 130", "Output/Plots=false"});
  p.output.directory = "test_evaluation_summary";
  std::filesystem::remove_all(p.output.directory);
  std::filesystem::create_directories(p.output.directory);
  std::ostringstream screen;
  RunPhase phase(p.output.directory, false);
  run_dynamics(p, screen, phase);
  const auto summary =
      nlohmann::json::parse(text_of(p.output.directory + "/summary.json"));
  const auto& s = summary["pantographs"][0]["statistics"];
  EXPECT_EQ(summary["statistics"], s);
  EXPECT_EQ(s["window"]["x"], nlohmann::json::array({0, 130}));
  EXPECT_EQ(s["window"]["spans"], nlohmann::json::array({1, 2}));
  for (const char* set : {"raw", "filtered"})
  {
    std::vector<std::string> keys;
    for (const auto& [key, value] : s[set].items())
      keys.push_back(key);
    std::sort(keys.begin(), keys.end());
    std::vector<std::string> expected{
        "contact_loss_percent", "max", "mean", "mean_minus_3std",
        "mean_plus_3std",       "min", "std"};
    if (std::string(set) == "filtered")
      expected.insert(expected.end(), {"cutoff_hz", "order"});
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(keys, expected) << set;
  }
  EXPECT_EQ(s["filtered"]["cutoff_hz"], 20);
  EXPECT_EQ(s["filtered"]["order"], 4);
  const std::string csv = text_of(p.output.directory + "/time_series.csv");
  ASSERT_EQ(s["steady_arms"].size(), 2u);
  const double rise_65 = largest_rise(csv, "w_w(65)"),
               rise_130 = largest_rise(csv, "w_w(130)");
  EXPECT_EQ(s["steady_arms"][0]["x"], 65);
  EXPECT_NEAR(s["steady_arms"][0]["max_uplift_m"].get<double>(), rise_65, 1e-11);
  EXPECT_EQ(s["steady_arms"][1]["x"], 130);
  EXPECT_NEAR(s["steady_arms"][1]["max_uplift_m"].get<double>(), rise_130, 1e-11);
  EXPECT_NEAR(s["max_steady_arm_uplift_m"].get<double>(), std::max(rise_65, rise_130),
              1e-11);
  // Dropper slack events: one per interval, per dropper and in total.
  const auto& intervals = summary["dropper_slack_intervals"];
  const auto& events = summary["dropper_slack_events"];
  ASSERT_EQ(events["per_dropper"].size(), intervals.size());
  unsigned long total = 0;
  for (std::size_t j = 0; j < intervals.size(); ++j)
  {
    EXPECT_EQ(events["per_dropper"][j].get<unsigned long>(), intervals[j].size());
    total += intervals[j].size();
  }
  EXPECT_EQ(events["total"].get<unsigned long>(), total);
  // The screen: raw and filtered side by side, the window in metres and spans.
  EXPECT_NE(screen.str().find("x_p in [0, 130] m (spans 1-2)"), std::string::npos)
      << screen.str();
  EXPECT_NE(screen.str().find("max uplift at the steady arms in the window"),
            std::string::npos);
}

// ---------------------------------------------------------------- plot
// The script of contact_force_over_x: a dashed line at each support inside
// the run's x range (not at those outside), the spans numbered, the window
// shaded (clipped to the range), raw and filtered curves found by name.
TEST(ContactForceOverX, ScriptMarksSupportsSpansAndTheWindow)
{
  const std::string dir = "test_evaluation_plot";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  ContactForceStatistics s;
  s.window = {220., 330., 5, 6};
  s.filtered = ForceFigures{};
  s.filter_cutoff_hz = 20.;
  s.filter_order = 4;
  const std::vector<std::string> columns{
      "t",      "x_p[1]",      "lambda_p[1]",         "lambda_p_filtered[1]",
      "x_p[2]", "lambda_p[2]", "lambda_p_filtered[2]"};
  const ForceOverXPlot plot{contact_force_over_x_file("pantograph 2", true),
                            "pantograph 2",
                            "[2]",
                            100.,
                            300.,
                            &s};
  EXPECT_EQ(plot.png, "contact_force_over_x_pantograph_2.png");
  EXPECT_EQ(contact_force_over_x_file("pantograph", false), "contact_force_over_x.png");
  {
    // Pantograph 2's x_p, lambda_p and lambda_p_filtered are columns 5 to 7.
    std::ofstream csv(dir + "/contact_force.csv");
    csv << "t,x_p[1],lambda_p[1],lambda_p_filtered[1],x_p[2],lambda_p[2],"
           "lambda_p_filtered[2]\n"
        << "0,300,1,2,100,150.5,151.5\n0.1,310,3,4,300,160.25,159.75\n";
  }
  plot_contact_force_over_x(dir, columns, {plot}, s55_supports(), "test");
  const std::string gp = text_of(dir + "/contact_force_over_x.gp");
  for (const char* x : {"110", "165", "220", "275"})
    EXPECT_NE(gp.find(std::string("set arrow from first ") + x + ", graph 0"),
              std::string::npos)
        << x << '\n'
        << gp;
  for (const char* x : {"55,", "330,"}) // outside [100, 300] m
    EXPECT_EQ(gp.find(std::string("set arrow from first ") + x), std::string::npos) << gp;
  EXPECT_NE(gp.find("set label 'span 3' at first 137.5"), std::string::npos) << gp;
  EXPECT_NE(gp.find("set object rectangle from first 220, graph 0 to first 300, graph 1"),
            std::string::npos)
      << gp;
  // The curves are pantograph 2's columns, inline.
  EXPECT_NE(gp.find("$raw << EOD\n100 150.5\n300 160.25\nEOD\n"), std::string::npos)
      << gp;
  EXPECT_NE(gp.find("$filtered << EOD\n100 151.5\n300 159.75\nEOD\n"), std::string::npos)
      << gp;
  EXPECT_NE(gp.find("plot $raw using 1:2 with lines"), std::string::npos) << gp;
  EXPECT_NE(gp.find("$filtered using 1:2 with lines"), std::string::npos) << gp;
  EXPECT_NE(
      gp.find("set output output_directory.'contact_force_over_x_pantograph_2.png'"),
      std::string::npos)
      << gp;
}
