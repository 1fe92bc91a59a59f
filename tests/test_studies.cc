// Refinement studies (issue 5): observed orders in time of the half-explicit
// method and BDF-2 on a smooth bilateral case, the comparison of time series
// on nested and non-nested grids, the refusal of unstable half-explicit steps,
// and the transfer of run outcomes between MPI ranks.
#include <pantocat/app/program_parameters.h>
#include <pantocat/base/input_error.h>
#include <pantocat/simulation/switch_episodes.h>
#include <pantocat/studies/contact_convergence.h>
#include <pantocat/studies/convergence_study.h>
#include <pantocat/studies/series_comparison.h>
#include <pantocat/studies/study_plan.h>
#include <pantocat/studies/study_run.h>
#include <pantocat/studies/work_precision_study.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

using namespace pantocat;

namespace
{
/**
 * The smooth case: the paper's catenary and pantograph on a coarse FDM grid
 * (N+1 = 50), droppers and contact bilateral (no switching), x_p from 2 m to
 * 3.6 m at 32 m/s (t_e = 0.05 s); dt = 1e-4, 5e-5, 2.5e-5 s against
 * dt = 3.125e-6 s (the finest entry, 8 times below the finest studied step).
 */
ProgramParameters smooth_bilateral_case(const std::string& integrator)
{
  ProgramParameters p;
  p.mode = RunMode::convergence_study;
  p.pantograph().final_position = 3.6;
  p.scene.droppers = DropperModel::bilateral;
  p.scene.pantographs[0].contact = Constraint::Kind::bilateral;
  p.discretisation.method = SpaceMethod::fdm;
  p.discretisation.n_intervals = 50;
  p.study.integrators = {integrator};
  p.study.time_steps = {1e-4, 5e-5, 2.5e-5, 3.125e-6};
  p.study.eigenfrequency_errors = false;
  return p;
}

void expect_second_order_in_time(const std::string& integrator)
{
  ConvergenceStudy study(smooth_bilateral_case(integrator).make_study_case());
  study.run();
  const auto& rows = study.rows(0);
  ASSERT_EQ(rows.size(), 3u);
  std::vector<double> l2, max, wire;
  for (const auto& r : rows)
  {
    ASSERT_EQ(r.status, RunOutcome::Status::completed) << r.message;
    EXPECT_FALSE(r.lambda_p.interpolated); // 3.125e-6 divides every step
    l2.push_back(r.lambda_p.l2);
    max.push_back(r.lambda_p.max);
    wire.push_back(r.wire.l2);
  }
  const auto dt = study.refinement_parameters(0);
  // Order 2 +/- 0.2 on the last halving (5e-5 -> 2.5e-5 s): the reference's
  // own error is (1/8)^2 = 1/64 of the finest run's and moves the order by
  // less than 0.03; the higher-order terms still visible one halving earlier
  // (orders 2.1-2.5 from 1e-4 to 5e-5 s) fall by a factor 4 per halving. An
  // order-1 or order-3 method fails the test.
  for (const auto* e : {&l2, &max, &wire})
  {
    const double order = observed_orders(*e, dt).back();
    EXPECT_NEAR(order, 2., 0.2) << integrator;
  }
  // The errors are small compared with lambda_p itself (~ 100 N on this grid).
  EXPECT_LT(max.back(), 0.1);
}
} // namespace

TEST(ConvergenceInTime, HalfExplicitIsSecondOrderOnASmoothBilateralCase)
{
  expect_second_order_in_time("half-explicit");
}

TEST(ConvergenceInTime, Bdf2IsSecondOrderOnASmoothBilateralCase)
{
  expect_second_order_in_time("bdf2");
}

TEST(SeriesComparison, NestedGridsAreComparedExactlyOthersInterpolated)
{
  // y = t^2 on [0, 1]: the reference (dt = 0.01) holds every point of a run
  // with dt = 0.04 (no interpolation, error 0); for dt = 0.03 the linear
  // interpolant of t^2 errs by at most dt_ref^2 / 8 * max|y''| = 2.5e-5.
  const auto series = [](const double dt)
  {
    std::pair<std::vector<double>, std::vector<double>> s;
    const int n = static_cast<int>(std::round(1. / dt));
    for (int i = 0; i <= n; ++i)
      s.first.push_back(i * dt), s.second.push_back(i * dt * i * dt);
    return s;
  };
  const auto ref = series(0.01);
  const auto nested = series(0.04);
  const SeriesErrors e =
      compare_series(nested.first, nested.second, ref.first, ref.second);
  EXPECT_FALSE(e.interpolated);
  EXPECT_LT(e.max, 1e-15);
  const auto other = series(1. / 33.);
  const SeriesErrors f = compare_series(other.first, other.second, ref.first, ref.second);
  EXPECT_TRUE(f.interpolated);
  EXPECT_LE(f.max, 2.5e-5 + 1e-15);
  EXPECT_GT(f.max, 1e-6); // the interpolation error is there, not hidden
  // A constant offset of 1 in a run: L2 (RMS over time) and max norm are 1.
  auto shifted = nested;
  for (double& y : shifted.second)
    y += 1.;
  const SeriesErrors g =
      compare_series(shifted.first, shifted.second, ref.first, ref.second);
  EXPECT_NEAR(g.l2, 1., 1e-12);
  EXPECT_NEAR(g.max, 1., 1e-12);
  EXPECT_NEAR(g.relative_peak, 1., 1e-12); // max y_ref = 1
}

TEST(SeriesComparison, ProfileNormsOfALinearError)
{
  // e(x) = x on [0, 2]: ||e||_L2 = sqrt(8/3) (trapezoidal rule: + h^2 terms),
  // |e|_H1 = sqrt(2) exactly.
  std::vector<double> w(201), zero(201, 0.);
  for (int j = 0; j <= 200; ++j)
    w[j] = 2. * j / 200.;
  const ProfileErrors e = compare_profiles(w, zero, 2.);
  EXPECT_NEAR(e.l2, std::sqrt(8. / 3.), 1e-4); // trapezoidal error h^2/6 * 2 = 3.3e-5
  EXPECT_NEAR(e.h1, std::sqrt(2.), 1e-12);
}

TEST(StudyRun, HalfExplicitStepAboveTheStabilityLimitIsSkippedAndReported)
{
  // FDM, N+1 = 500: 2/omega_max = 6.62e-5 s (Table 1 figure); dt = 1e-4 s is
  // refused by a dynamic run, so a study skips it and says why.
  ProgramParameters p;
  p.discretisation.method = SpaceMethod::fdm;
  p.pantograph().final_position = 2.32;
  const StudyRun run{SpaceMethod::fdm, "half-explicit", 500, 1e-4, false, {}, {}};
  const RunOutcome o = execute_study_run(run, p.make_case(), RunRequest());
  EXPECT_EQ(o.status, RunOutcome::Status::skipped);
  EXPECT_NE(o.message.find("6.62e-05"), std::string::npos) << o.message;
  EXPECT_TRUE(o.t.empty());
}

TEST(StudyRun, OutcomesSurviveThePackingForMpiExactly)
{
  RunOutcome o;
  o.status = RunOutcome::Status::failed;
  o.message = "active set cycles at t = 0.1 s";
  o.cpu_seconds = 1.25;
  o.steps = 12345;
  o.t = {0., 0.1, 0.2};
  o.lambda_p = {8.75, 100. / 3., -1e-300};
  o.wire = {0.1};
  o.f_min_carrier = 3.9528536;
  std::vector<char> buffer;
  o.pack(buffer);
  o.pack(buffer);
  std::size_t position = 0;
  RunOutcome::unpack(buffer, position);
  const RunOutcome u = RunOutcome::unpack(buffer, position);
  EXPECT_EQ(position, buffer.size());
  EXPECT_EQ(u.status, o.status);
  EXPECT_EQ(u.message, o.message);
  EXPECT_EQ(u.steps, o.steps);
  EXPECT_EQ(u.lambda_p, o.lambda_p); // bitwise: the MPI table equals the serial one
  EXPECT_EQ(u.t, o.t);
  EXPECT_EQ(u.wire, o.wire);
  EXPECT_EQ(u.f_min_carrier, o.f_min_carrier);
}

TEST(StudyRun, ContactFiguresSurviveThePackingForMpiExactly)
{
  // Every field bit for bit, NaN (no low pass) included: the contact table of
  // 2 ranks equals the serial one.
  RunOutcome o;
  o.contact.loss_percent = 100. / 3.;
  o.contact.filtered_max = 123.456789012345;
  o.contact.filtered_min = -1e-300;
  o.contact.filtered_std = std::numeric_limits<double>::quiet_NaN();
  o.contact.min_unilateral_force = -1211.25;
  o.contact.min_unilateral_constraint = "dropper 2";
  o.contact.min_unilateral_time = 0.2604;
  o.contact.contact = 7;
  o.contact.events = {{0.1, 7, false}, {0.125, 7, true}, {0.25, 1, false}};
  o.contact.short_episodes = 3;
  o.contact.short_episode_time = 3.7e-4;
  o.lambda_p = {1.};
  std::vector<char> buffer;
  o.pack(buffer);
  std::size_t position = 0;
  const RunOutcome u = RunOutcome::unpack(buffer, position);
  EXPECT_EQ(position, buffer.size());
  std::vector<char> again;
  u.pack(again);
  EXPECT_EQ(again, buffer); // bitwise, NaN included
  EXPECT_EQ(u.contact.min_unilateral_constraint, "dropper 2");
  EXPECT_EQ(u.contact.min_unilateral_force, -1211.25);
  EXPECT_EQ(u.contact.short_episodes, 3u);
  EXPECT_EQ(u.contact.short_episode_time, 3.7e-4);
  ASSERT_EQ(u.contact.events.size(), 3u);
  EXPECT_EQ(u.contact.events[1].t, 0.125);
  EXPECT_TRUE(u.contact.events[1].closes);
  EXPECT_EQ(u.contact.events[2].constraint, 1u);
  EXPECT_EQ(u.contact.contact_events(), 2u);
  EXPECT_TRUE(std::isnan(u.contact.filtered_std));
}

namespace
{
/// A completed run at step @p dt with the given figures and events.
ContactConvergence::Run synthetic_run(const double dt, const ContactFigures& f)
{
  ContactConvergence::Run r;
  r.run = StudyRun{SpaceMethod::fdm, "bdf2", 500, dt, false, {}, {}};
  r.contact_law = "unilateral";
  r.figures = f;
  return r;
}

/**
 * Figures with known errors in dt: loss 2 + 100 dt (order 1), filtered max
 * 200 + 1e6 dt^2 and min 50 - 1e6 dt^2 (order 2), std 30 (exact), the
 * contact (constraint 7) lost at 0.1 + dt and back at 0.12 + 2 dt (order 1),
 * dropper 0 slack at 0.05 + 1e3 dt^2 (order 2).
 */
ContactFigures synthetic_figures(const double dt)
{
  ContactFigures f;
  f.loss_percent = 2. + 100. * dt;
  f.filtered_max = 200. + 1e6 * dt * dt;
  f.filtered_min = 50. - 1e6 * dt * dt;
  f.filtered_std = 30.;
  f.min_unilateral_force = 0.;
  f.min_unilateral_constraint = "contact";
  f.contact = 7;
  f.events = {
      {0.05 + 1e3 * dt * dt, 0, false}, {0.1 + dt, 7, false}, {0.12 + 2. * dt, 7, true}};
  return f;
}
} // namespace

TEST(ContactConvergence, DifferencesOrdersAndEventTimesOfSyntheticNumbers)
{
  const std::vector<double> dt = {1e-3, 5e-4, 2.5e-4, 1.25e-4};
  std::vector<ContactConvergence::Run> runs;
  for (const double s : dt)
    runs.push_back(synthetic_run(s, synthetic_figures(s)));
  const ContactConvergence c(runs, dt);
  const auto& q = c.quantities();
  ASSERT_EQ(q.size(), 4u);
  // |x(dt) - x(dt/2)| on the finer run's line: loss 100 dt/2, max 1e6 * 3/4 dt^2.
  EXPECT_TRUE(std::isnan(q[0].differences[0]));
  EXPECT_NEAR(q[0].differences[1], 100. * 5e-4, 1e-12);
  EXPECT_NEAR(q[1].differences[3], 0.75e6 * 2.5e-4 * 2.5e-4, 1e-9);
  // Exact orders 1 (loss), 2 (max, min) from the second difference on; only
  // rounding of the figures (1e-13 relative) is left: 1e-6.
  for (const std::size_t k : {2u, 3u})
  {
    EXPECT_NEAR(q[0].orders[k], 1., 1e-6);
    EXPECT_NEAR(q[1].orders[k], 2., 1e-6);
    EXPECT_NEAR(q[2].orders[k], 2., 1e-6);
    EXPECT_EQ(q[3].differences[k], 0.);      // std exact: no difference ...
    EXPECT_TRUE(std::isnan(q[3].orders[k])); // ... and no order
  }
  EXPECT_TRUE(std::isnan(q[1].orders[1])); // one difference: no order yet
  // Contact events: the return moves by 2 (dt - dt/2) = dt, order 1; all
  // events: the same maximum (the dropper moves by 1e3 * 3/4 dt^2 < dt).
  for (const std::size_t k : {1u, 2u, 3u})
  {
    EXPECT_TRUE(c.contact_event_times()[k].match);
    EXPECT_EQ(c.contact_event_times()[k].count_a, 2u);
    EXPECT_NEAR(c.contact_event_times()[k].max_difference, dt[k - 1], 1e-15);
    EXPECT_NEAR(c.event_times()[k].max_difference, dt[k - 1], 1e-15);
    EXPECT_EQ(c.event_times()[k].count_b, 3u);
  }
  EXPECT_NEAR(c.contact_event_orders()[3], 1., 1e-6);
  EXPECT_NEAR(c.event_orders()[2], 1., 1e-6);
}

TEST(ContactConvergence, EventsThatDoNotMatchAndFailedRunsGiveNoDifference)
{
  const std::vector<double> dt = {1e-3, 5e-4, 2.5e-4};
  std::vector<ContactConvergence::Run> runs;
  for (const double s : dt)
    runs.push_back(synthetic_run(s, synthetic_figures(s)));
  // The middle run loses the contact once more (a one-step opening): the
  // contact's counts differ on both sides of it, the dropper's still match.
  runs[1].figures.events.push_back({0.2, 7, false});
  ContactConvergence c(runs, dt);
  EXPECT_FALSE(c.contact_event_times()[1].match);
  EXPECT_EQ(c.contact_event_times()[1].count_a, 2u);
  EXPECT_EQ(c.contact_event_times()[1].count_b, 3u);
  EXPECT_TRUE(std::isnan(c.contact_event_times()[1].max_difference));
  EXPECT_FALSE(c.event_times()[2].match);
  std::ostringstream text;
  c.write_text(text, false);
  EXPECT_NE(text.str().find("2 vs 3: counts differ"), std::string::npos) << text.str();

  // The same number of switches but opening instead of closing: no match either.
  EventTimeDifference d = compare_event_times({{0.1, 7, false}}, {{0.1, 7, true}});
  EXPECT_FALSE(d.match);
  // Two constraints whose switches swap order (0.1 / 0.1001 against 0.1002 /
  // 0.0999) are matched per constraint: max difference 2e-4 s.
  d = compare_event_times({{0.1, 0, false}, {0.1001, 1, false}},
                          {{0.0999, 1, false}, {0.1002, 0, false}});
  EXPECT_TRUE(d.match);
  EXPECT_NEAR(d.max_difference, 2e-4, 1e-15);
  // The same time point reached as 3 * 0.1 and 0.3 (5.6e-17 s apart) at two
  // steps is no difference: rounding below 1e-12 s counts as 0 (no order).
  d = compare_event_times({{3 * 0.1, 7, false}}, {{0.3, 7, false}});
  EXPECT_TRUE(d.match);
  EXPECT_EQ(d.max_difference, 0.);
  // No events in either run: they match with difference 0.
  d = compare_event_times({}, {});
  EXPECT_TRUE(d.match);
  EXPECT_EQ(d.max_difference, 0.);

  // A failed middle run: no difference on either side of it, and its line says why.
  runs[1].status = RunOutcome::Status::failed;
  runs[1].message = "unstable at t = 0.2 s";
  const ContactConvergence f(runs, dt);
  EXPECT_TRUE(std::isnan(f.quantities()[1].differences[1]));
  EXPECT_TRUE(std::isnan(f.quantities()[1].differences[2]));
  EXPECT_FALSE(f.event_times()[2].match);
  std::ostringstream csv;
  f.write_csv(csv);
  // One line per run, each with as many fields as the header.
  const auto fields = [](const std::string& line)
  { return std::count(line.begin(), line.end(), ',') + 1; };
  std::istringstream lines(csv.str());
  std::string line;
  unsigned int n = 0;
  while (std::getline(lines, line))
  {
    EXPECT_EQ(fields(line), fields(ContactConvergence::csv_header())) << line;
    ++n;
  }
  EXPECT_EQ(n, 3u);
  EXPECT_NE(csv.str().find(",failed,"), std::string::npos);
  EXPECT_EQ(csv.str().find("differ"), std::string::npos); // not compared: empty
}

namespace
{
/// The switches of constraint @p c that time points n dt see of the open
/// intervals @p open: each at the first time point with the new state.
std::vector<StudyEvent> sampled_switches(const std::vector<Interval>& open,
                                         const double dt, const double end,
                                         const unsigned int c)
{
  const auto is_open = [&](const double t)
  {
    return std::any_of(open.begin(), open.end(),
                       [&](const Interval& i) { return t >= i.first && t < i.second; });
  };
  std::vector<StudyEvent> events;
  bool was = false;
  for (unsigned long n = 0; n * dt <= end; ++n)
    if (const bool now = is_open(n * dt); now != was)
    {
      events.push_back({n * dt, c, !now});
      was = now;
    }
  return events;
}
} // namespace

TEST(SwitchEpisodes, ReclosuresShorterThanTheGapMerge)
{
  // Two intervals 0.5 ms apart merge at a gap of 1 ms (open 1.9995 s of the
  // 2 s span), the third (1 s later) stays apart; gap 0 merges nothing.
  const std::vector<Interval> open{{0., 1.}, {1.0005, 2.}, {3., 4.}};
  const std::vector<SwitchEpisode> e = switch_episodes(open, 1e-3);
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0].span, Interval(0., 2.));
  EXPECT_EQ(e[0].intervals, 2u);
  EXPECT_NEAR(e[0].open_time, 1.9995, 1e-12);
  EXPECT_EQ(e[1].intervals, 1u);
  EXPECT_EQ(switch_episodes(open, 0.).size(), 3u);
  EXPECT_TRUE(switch_episodes({}, 1e-3).empty());
}

TEST(SwitchEpisodes, TheEventsOfACascadeConvergeAsEpisodes)
{
  // A Zeno cascade: the contact opens at 0.260013 s for 0.41 ms, then recloses and
  // opens again for ever shorter times (ratio 1/2, 12 intervals, all within
  // 1.64 ms). A step dt resolves the intervals longer than about dt, so the
  // raw event counts grow under halving (10, 12, 14, 16 switches: the fig3
  // lists at 65 m/s); merged at a gap of 1 ms every step size sees one
  // episode, open at the first time point after the opening and closed at the
  // first after the last resolved reclosure: the episode's events agree to
  // one step of the coarser run (here exactly the finer step: order 1).
  std::vector<Interval> cascade;
  double t = 0.260013, d = 4.1e-4;
  for (int k = 0; k < 12; ++k, d *= 0.5)
  {
    cascade.push_back({t, t + d});
    t += 2. * d;
  }
  const double end = 0.27;
  std::vector<std::vector<StudyEvent>> raw, merged;
  for (const double dt : {5e-5, 2.5e-5, 1.25e-5, 6.25e-6})
  {
    raw.push_back(sampled_switches(cascade, dt, end, 7));
    merged.push_back(episode_events(raw.back(), 1e-3).events);
  }
  EXPECT_LT(raw[0].size(), raw[3].size()); // more of the cascade resolved
  for (std::size_t k = 0; k < merged.size(); ++k)
  {
    ASSERT_EQ(merged[k].size(), 2u) << k;
    EXPECT_FALSE(merged[k][0].closes);
    EXPECT_TRUE(merged[k][1].closes);
  }
  for (std::size_t k = 1; k < merged.size(); ++k)
  {
    EXPECT_FALSE(compare_event_times(raw[k - 1], raw[k]).match) << k;
    const EventTimeDifference d = compare_event_times(merged[k - 1], merged[k]);
    EXPECT_TRUE(d.match) << k;
    EXPECT_LE(d.max_difference, 5e-5 / (1 << (k - 1)) + 1e-15) << k;
  }
  // A closing followed by an opening of another constraint is not merged.
  const std::vector<StudyEvent> two{{0.1, 1, true}, {0.1001, 2, false}};
  EXPECT_EQ(episode_events(two, 1e-3).events.size(), 2u);
  // An isolated separation of 0.1 ms (a head leaving a wire just stopped
  // under it) is a short episode: counted with its length, not matched; one
  // of 2 ms and a constraint open from the start are kept.
  const EpisodeEvents e = episode_events({{0.05, 3, true},
                                          {0.1, 7, false},
                                          {0.1001, 7, true},
                                          {0.2, 7, false},
                                          {0.202, 7, true}},
                                         1e-3);
  ASSERT_EQ(e.events.size(), 3u);
  EXPECT_EQ(e.events[0].constraint, 3u);
  EXPECT_EQ(e.events[1].t, 0.2);
  EXPECT_EQ(e.short_episodes, 1u);
  EXPECT_NEAR(e.short_episode_time, 1e-4, 1e-15);
}

TEST(StudyPlan, WorkPrecisionNeedsASeparateReference)
{
  ProgramParameters p;
  p.mode = RunMode::work_precision;
  p.study.time_steps = {1e-4, 5e-5};
  try
  {
    WorkPrecisionStudy study(p.make_study_case());
    FAIL() << "no InputError";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("Study/Reference = finest run"),
              std::string::npos)
        << e.what();
  }
}

TEST(StudyPlan, AllCombinationsRunEveryGridWithEveryStep)
{
  // 2 discretisations x 1 integrator x (2 grids x 3 steps) + 1 reference = 13 runs.
  ProgramParameters p;
  p.mode = RunMode::work_precision;
  p.study.discretisations = {SpaceMethod::fdm, SpaceMethod::fem};
  p.study.integrators = {"bdf2"};
  p.study.n_intervals = {250, 500};
  p.study.time_steps = {1e-4, 5e-5, 2e-5};
  p.study.all_combinations = true;
  p.study.reference = StudyReference::separate_run;
  const StudyPlan plan(p.make_study_case());
  ASSERT_EQ(plan.runs().size(), 13u);
  EXPECT_EQ(plan.n_refinements(), 6u);
  const StudyRun& r = plan.runs()[plan.index(1, 4)]; // fem, second grid, second step
  EXPECT_EQ(r.discretisation, SpaceMethod::fem);
  EXPECT_EQ(r.n_intervals, 500u);
  EXPECT_EQ(r.time_step, 5e-5);
  EXPECT_TRUE(plan.runs().back().reference);
  EXPECT_EQ(plan.reference_index(0), 12u);
}

namespace
{
/// prm/benchmark-32.prm (FDM, N+1 = 500, x_p 2 -> 18 m) with @p overrides.
ProgramParameters benchmark_32(const std::vector<std::string>& overrides)
{
  dealii::ParameterHandler prm;
  read_program_parameters(prm, std::string(PANTOCAT_SOURCE_DIR) + "/prm/benchmark-32.prm",
                          overrides);
  ProgramParameters p;
  p.parse_parameters(prm);
  return p;
}
} // namespace

TEST(ContactStatisticsStudy, Bdf2At32MetresPerSecondKeepsContactAndItsExtremesConverge)
{
  // The paper's case at 32 m/s (no switch), BDF-2, dt = 1e-4 ... 1.25e-5 s,
  // 20 Hz low pass over the whole run (0.5 s); about 5 s of CPU time.
  const ProgramParameters p = benchmark_32(
      {"Run/Mode=convergence study", "Statistics/Low-pass cut-off=20",
       "Study/Integrators=bdf2", "Study/Time steps=1e-4, 5e-5, 2.5e-5, 1.25e-5",
       "Study/Quantities=contact statistics"});
  ConvergenceStudy study(p.make_study_case());
  study.run();
  const ContactConvergence& c = study.contact(0);
  ASSERT_EQ(c.runs().size(), 4u);
  for (const auto& r : c.runs())
  {
    ASSERT_EQ(r.status, RunOutcome::Status::completed) << r.message;
    // Nothing switches at 32 m/s: no loss, no event; the smallest unilateral
    // force is the contact's 0.016 s after the start (5.5 N; 1 N of margin
    // for the step).
    EXPECT_EQ(r.figures.loss_percent, 0.);
    EXPECT_TRUE(r.figures.events.empty());
    EXPECT_GT(r.figures.min_unilateral_force, 4.5);
    EXPECT_EQ(r.figures.min_unilateral_constraint, "contact");
    EXPECT_NEAR(r.figures.filtered_max, 106.99, 0.02); // measured 106.986-106.989 N
  }
  for (const std::size_t k : {1u, 2u, 3u})
  {
    EXPECT_EQ(c.quantities()[0].differences[k], 0.);
    EXPECT_TRUE(c.event_times()[k].match);
    EXPECT_EQ(c.event_times()[k].max_difference, 0.);
  }
  // The filtered max and min converge with BDF-2's order 2 (measured on the
  // last halving: 2.03 and 1.99; one halving earlier 2.12 and 1.64). +/- 0.25:
  // besides BDF-2's error, an extreme sampled at the time points errs by up to
  // dt^2/8 |f''|, of the same order but not smooth in dt (1.64 above).
  EXPECT_NEAR(c.quantities()[1].orders[3], 2., 0.25);
  EXPECT_NEAR(c.quantities()[2].orders[3], 2., 0.25);
  // sigma: the successive differences shrink more than twofold per halving
  // (measured 2.4e-3, 4.2e-4, 9.8e-5 N) and stay below 1e-3 N. Order 2 is not
  // asserted: sigma over the time points is a rectangle rule with both ends
  // weighted fully, which adds a * dt to it (a = 45 N/s here: the population
  // sigma minus the trapezoidal one of the dt = 1.25e-5 s run, 5.6e-4 N); that
  // first-order term takes over below dt = 1.25e-5 s (order -1.4 at 6.25e-6 s).
  const auto& sigma = c.quantities()[3].differences;
  EXPECT_LT(sigma[2], sigma[1] / 2.);
  EXPECT_LT(sigma[3], sigma[2] / 2.);
  EXPECT_LT(sigma[3], 1e-3);
}

TEST(StudyPlan, ContactLawsAreADimensionOfTheStudy)
{
  // 1 discretisation (the default, FEM) x 2 integrators x 2 contact laws = 4
  // methods of 2 runs.
  ProgramParameters p;
  p.mode = RunMode::convergence_study;
  p.study.integrators = {"bdf2", "ida"};
  p.study.contact_laws = {"unilateral", "penalty"};
  p.study.penalty = {5e4, 10.};
  p.study.time_steps = {1e-4, 5e-5};
  const StudyCase base = p.make_study_case();
  const StudyPlan plan(base);
  ASSERT_EQ(plan.n_methods(), 4u);
  const StudyRun& penalty = plan.runs()[plan.index(1, 0)];    // bdf2, penalty
  EXPECT_EQ(penalty.method(), "fem + bdf2, penalty contact"); // the default: FEM
  const Case c = penalty.parameters(base);
  EXPECT_EQ(c.scene.pantographs[0].contact_law(), "penalty");
  EXPECT_EQ(c.scene.pantographs[0].contact_compliance.stiffness, 5e4);
  EXPECT_EQ(c.scene.pantographs[0].contact_compliance.damping, 10.);
  const StudyRun& rigid = plan.runs()[plan.index(2, 1)]; // ida, unilateral
  EXPECT_EQ(rigid.parameters(base).scene.pantographs[0].contact_law(), "unilateral");
  EXPECT_EQ(rigid.time_step, 5e-5);
  // Without Contact laws the case's own law, unnamed in the method.
  p.study.contact_laws.clear();
  const StudyPlan own(p.make_study_case());
  EXPECT_EQ(own.n_methods(), 2u);
  EXPECT_EQ(own.runs()[0].method(), "fem + bdf2");
  EXPECT_EQ(own.runs()[0].contact_law_in(base), "unilateral");
}
