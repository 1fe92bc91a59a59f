// Input that broke the program's promises: each case is now refused with an
// InputError before anything runs (or, for a run, stopped with a
// SimulationError), instead of a crash, a hang or an allocation failure.
#include <pantocat/analysis/stability_limit.h>
#include <pantocat/app/parameter_input.h>
#include <pantocat/app/program_parameters.h>
#include <pantocat/base/input_error.h>
#include <pantocat/io/external_program.h>
#include <pantocat/io/output_parameters.h>
#include <pantocat/io/plots.h>
#include <pantocat/lac/vector_bounds.h>
#include <pantocat/simulation/case_runner.h>
#include <pantocat/space/discretisation_parameters.h>
#include <pantocat/time/integrator_registry.h>
#include <pantocat/time/time_integrator.h>

#include "support/case_files.h"
#include "support/input_errors.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>

using namespace pantocat;

TEST(Robustness, EveryIntegratorRefusesASystemWithoutUnknowns)
{
  const SemiDiscreteSystem empty;
  for (const IntegratorEntry& entry : registered_integrators())
  {
    TimeIntegrationParameters p;
    p.integrator = entry.name;
    const std::string message = input_error_of([&] { create_time_integrator(empty, p); });
    EXPECT_NE(message.find("the scene has no unknowns"), std::string::npos) << message;
  }
}

TEST(Robustness, AScenarioWithoutUnknownsIsRefusedWithItsParameters)
{
  dealii::ParameterHandler prm;
  ProgramParameters::declare_parameters(prm);
  prm.parse_input_from_string("subsection Scene\n set Messenger = rigid\n"
                              " set Contact wire = rigid\n set Pantograph = absent\n"
                              " set Droppers = absent\nend\n");
  ProgramParameters p;
  const std::string message = input_error_of([&] { p.parse_parameters(prm); });
  EXPECT_EQ(message.rfind("Scene/Pantograph = absent: with Messenger = rigid and Contact "
                          "wire = rigid the scene has no unknowns",
                          0),
            0u)
      << message;
}

TEST(Robustness, AVtuIntervalBelowTheTimeStepIsRefused)
{
  OutputParameters p;
  p.vtu_interval = 1e-300;
  EXPECT_EQ(input_error_of([&] { p.check(5e-5, 20.); }),
            "Output/VTU interval = 1e-300: must be 0 (no frames) or at least Time "
            "integration/Time step = 5e-05 s (a frame every time step)");
  for (const double ok : {0., 5e-5, 0.01})
  {
    p.vtu_interval = ok;
    EXPECT_NO_THROW(p.check(5e-5, 20.));
  }
}

TEST(Robustness, AGridThatCannotFitIntoMemoryIsRefusedWithTheEstimate)
{
  ASSERT_GT(physical_memory_bytes(), 0.);
  DiscretisationParameters d;
  d.n_intervals = 2147483647;
  const std::string message = input_error_of([&] { d.check(20.); });
  EXPECT_EQ(message.rfind("Discretisation/Number of intervals = 2147483647: a run on "
                          "this grid needs about 6.87e+04 GB of memory",
                          0),
            0u)
      << message;
  d.n_intervals = 8000; // the finest grid of the stress suite: 0.26 GB
  EXPECT_NO_THROW(d.check(20.));
}

TEST(Robustness, ParameterFilesThatIncludeThemselvesAreRefused)
{
  const std::filesystem::path dir = "test_robustness_includes";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "sub");
  std::ofstream(dir / "self.prm")
      << "# a comment\ninclude " << (dir / "self.prm").string() << "\n";
  std::ofstream(dir / "a.prm") << "include " << (dir / "b.prm").string() << '\n';
  std::ofstream(dir / "b.prm") << "include " << (dir / "a.prm").string() << " # back\n";
  std::ofstream(dir / "fine.prm") << "include " << (dir / "leaf.prm").string() << '\n'
                                  << "include " << (dir / "leaf.prm").string() << '\n';
  std::ofstream(dir / "leaf.prm") << "subsection Catenary\nend\n";
  std::ofstream(dir / "subdir.prm") << "include " << (dir / "sub").string() << '\n';
  for (const char* file : {"self.prm", "a.prm"})
    EXPECT_NE(input_error_of([&] { check_parameter_file((dir / file).string()); })
                  .find("include cycle"),
              std::string::npos)
        << file;
  EXPECT_NE(input_error_of([&] { check_parameter_file((dir / "subdir.prm").string()); })
                .find("this is a directory"),
            std::string::npos);
  EXPECT_NE(input_error_of([&] { check_parameter_file((dir / "sub").string()); })
                .find("this is a directory"),
            std::string::npos);
  // The same file twice, but no cycle: fine.
  EXPECT_NO_THROW(check_parameter_file((dir / "fine.prm").string()));
}

TEST(Robustness, ExternalProgramsGetTheirArgumentsWithoutAShell)
{
  const std::string touch = find_program("touch");
  ASSERT_FALSE(touch.empty());
  EXPECT_EQ(touch.front(), '/');
  EXPECT_TRUE(find_program("no-such-program-pantocat").empty());
  const std::filesystem::path dir = "test_robustness_spawn";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  // One argument, in the working directory: a file of exactly that name.
  const std::string name = "a'; touch b; echo '$(touch c)";
  EXPECT_TRUE(run_program(touch, {name}, dir.string()));
  EXPECT_TRUE(std::filesystem::exists(dir / name));
  EXPECT_FALSE(std::filesystem::exists(dir / "b") || std::filesystem::exists(dir / "c") ||
               std::filesystem::exists("b") || std::filesystem::exists("c"));
  EXPECT_FALSE(run_program(find_program("false"), {}, dir.string()));
  EXPECT_FALSE(run_program(touch, {"x"}, (dir / "missing").string()));
}

TEST(Robustness, ErrorLinesArePrintable)
{
  EXPECT_EQ(printable_line("a\nb\x01"), "a\\x0ab\\x01");
}

TEST(Robustness, ValuesWithBracesAreCheckedAgainstTheirPatterns)
{
  const std::filesystem::path file = "test_robustness_braces.prm";
  std::ofstream(file) << "subsection Study\n  set Output name = caf\xe9 \xff\nend\n";
  const auto read = [&](const std::vector<std::string>& overrides)
  {
    dealii::ParameterHandler prm;
    ProgramParameters::declare_parameters(prm);
    return input_error_of([&] { read_parameter_file(prm, file.string(), overrides); });
  };
  // Bytes that are not UTF-8 (in the file) do not upset the check.
  EXPECT_EQ(read({}), "");
  EXPECT_EQ(read({"Output/Verbosity={x}"}),
            "Output/Verbosity = {x}: does not match the pattern [Selection "
            "quiet|normal|detailed ]");
  EXPECT_EQ(
      read({"Catenary/Span={abc}"}).rfind("Catenary/Span = {abc}: does not match", 0),
      0u);
  EXPECT_EQ(read({"Output/Output directory=out{1}"}), ""); // a file name may hold '{'
}

namespace
{
struct LastTimePoint : SimulationObserver
{
  void observe(const TimePoint& p) override
  {
    last = p;
    ++count;
  }
  TimePoint last;
  unsigned long count = 0;
};
} // namespace

TEST(Robustness, EveryIntegratorEndsExactlyAtTheFinalPosition)
{
  // The benchmark at 32 m/s from x_p = 2 to 4.7 m: t_e = 0.084375 s, which
  // neither dt divides. The last step used to run past the final position
  // (BDF-2, dt = 0.01 s: 21.2 m for 19.7 m); now the step is t_e / ceil(t_e /
  // dt), so the last time point is at t_e and x_p = 4.7 m up to rounding.
  // (half-explicit: 5.5e-5 s, below its limit with the moving contact; 6e-5 s
  // is refused since issue 17)
  for (const auto& [integrator, dt] :
       std::vector<std::pair<std::string, double>>{{"half-explicit", 5.5e-5},
                                                   {"bdf2", 0.01},
                                                   {"generalized-alpha", 0.01},
                                                   {"ida", 1e-3}})
  {
    dealii::ParameterHandler prm;
    read_program_parameters(
        prm, std::string(PANTOCAT_SOURCE_DIR) + "/prm/benchmark-32.prm",
        {"Pantograph/Final position=4.7", "Time integration/Integrator=" + integrator,
         "Time integration/Time step=" + std::to_string(dt)});
    ProgramParameters p;
    p.parse_parameters(prm);
    CaseRunner runner(p.make_case());
    const unsigned long n = static_cast<unsigned long>(std::ceil(0.084375 / dt));
    EXPECT_EQ(runner.number_of_steps(), n) << integrator;
    EXPECT_NEAR(runner.time_step(), 0.084375 / n, 1e-15) << integrator;
    EXPECT_LE(runner.time_step(), dt) << integrator;
    LastTimePoint last;
    runner.run({&last});
    EXPECT_NEAR(last.last.t, 0.084375, 1e-12) << integrator;
    ASSERT_EQ(last.last.x_p.size(), 1u);
    EXPECT_NEAR(last.last.x_p[0], 4.7, 1e-10) << integrator;
  }
}

TEST(Robustness, ARunWithASpeedRampEndsAtTheFinalPosition)
{
  // From rest to v_p in T_r, x_p(t) = x_0 + v_p (t - T_r / 2) after the ramp:
  // the run takes T_r / 2 longer than at v_p throughout. The benchmark at
  // 32 m/s with T_r = 0.2 s: t_e = 16 / 32 + 0.1 = 0.6 s (it used to end at
  // 0.5 s, x_p = 14.8 m). One pantograph, and two 3 m apart with the spacing
  // (the trailer 3 m short of 18 m); also two without a spacing, each with
  // its own positions, where the one that arrives first (pantograph 2, from
  // 6 m) ends the run. Tolerance: the last time point is t_e = n dt up to
  // rounding (1e-12 s), so x_p is the final position to 1e-9 m, far below one
  // step's travel (32 m/s x 5e-5 s = 1.6 mm).
  struct Run
  {
    std::vector<std::string> settings;
    double end_time;
    std::vector<double> final_positions;
  };
  const std::vector<Run> runs{
      {{"Pantograph/Speed ramp=0.2"}, 0.6, {18.}},
      {{"Pantograph/Speed ramp=0.2", "Scene/Number of pantographs=2",
        "Scene/Pantograph spacing=3", "Pantograph/Initial position=5"},
       13. / 32. + 0.1,
       {18., 15.}},
      {{"Pantograph/Speed ramp=0.2", "Scene/Number of pantographs=2",
        "Pantograph 2/Initial position=6"},
       12. / 32. + 0.1,
       {14., 18.}},
      // a run shorter than the ramp (3.2 m) ends inside it: t_e = sqrt(2 d T_r / v)
      {{"Pantograph/Speed ramp=0.2", "Pantograph/Final position=4"},
       std::sqrt(2. * 2. * 0.2 / 32.),
       {4.}}};
  for (const Run& r : runs)
  {
    std::vector<std::string> settings = r.settings;
    settings.push_back("Time integration/Time step=5e-5");
    std::string label;
    for (const std::string& setting : r.settings)
      label += setting + "; ";
    const ProgramParameters p =
        read_case(std::string(PANTOCAT_SOURCE_DIR) + "/prm/benchmark-32.prm", settings);
    CaseRunner runner(p.make_case());
    EXPECT_NEAR(runner.case_data().end_time(), r.end_time, 1e-15) << label;
    LastTimePoint last;
    runner.run({&last});
    EXPECT_NEAR(last.last.t, r.end_time, 1e-12) << label;
    ASSERT_EQ(last.last.x_p.size(), r.final_positions.size());
    for (std::size_t k = 0; k < r.final_positions.size(); ++k)
      EXPECT_NEAR(last.last.x_p[k], r.final_positions[k], 1e-9)
          << label << "pantograph " << k + 1;
  }
}

TEST(Robustness, AnEmptyLastListIsASpanWithoutDroppers)
{
  // Every ';' starts a list: "4.5, 27.5, 50.5; 10, 30; 5;" on four spans of
  // 55 m gives three droppers in span 1, two in span 2, one in span 3 and
  // none in span 4 (positions exact: sums of binary fractions and 55 k).
  const ProgramParameters p =
      read_case(std::string(PANTOCAT_SOURCE_DIR) + "/prm/benchmark-32.prm",
                {"Catenary/Span=55", "Catenary/Number of spans=4",
                 "Catenary/Droppers/Positions=4.5, 27.5, 50.5; 10, 30; 5;",
                 "Catenary/Droppers/Lengths=0.95, 0.95, 0.95, 0.95, 0.95, 0.95"});
  EXPECT_EQ(p.catenary.dropper_positions,
            (std::vector<double>{4.5, 27.5, 50.5, 65., 85., 115.}));
  EXPECT_EQ(p.catenary.dropper_spans, (std::vector<unsigned int>{0, 0, 0, 1, 1, 2}));
  // An empty list in the middle likewise; one list for all spans stays one list.
  const ProgramParameters middle = read_case(
      std::string(PANTOCAT_SOURCE_DIR) + "/prm/benchmark-32.prm",
      {"Catenary/Span=55", "Catenary/Number of spans=3",
       "Catenary/Droppers/Positions=4.5; ; 5", "Catenary/Droppers/Lengths=0.95, 0.95"});
  EXPECT_EQ(middle.catenary.dropper_positions, (std::vector<double>{4.5, 115.}));
  const ProgramParameters every =
      read_case(std::string(PANTOCAT_SOURCE_DIR) + "/prm/benchmark-32.prm",
                {"Catenary/Span=55", "Catenary/Number of spans=3",
                 "Catenary/Droppers/Positions=4.5", "Catenary/Droppers/Lengths=0.95"});
  EXPECT_EQ(every.catenary.dropper_positions, (std::vector<double>{4.5, 59.5, 114.5}));
}

TEST(Robustness, TheExplicitDampingBoundIsTheLimitTheStepMapFinds)
{
  // The half-explicit method takes a penalty contact's damping force
  // explicitly: stable only for dt c G M^-1 G^T <= 2 (explicit_damping_limit).
  // On the benchmark with c = 1.12e4 N s/m that bound (5.03e-5 s) is the
  // limit: the power iteration over the moving contact's one-step maps finds
  // its critical step within 2 % of it (the bisection's 1 %, and the bound is
  // a necessary condition: the critical step lies below it).
  const ProgramParameters p =
      read_case(std::string(PANTOCAT_SOURCE_DIR) + "/prm/benchmark-32.prm",
                {"Scene/Contact=penalty", "Scene/Contact damping=11200"});
  const CaseRunner runner(p.make_case());
  const ExplicitDampingLimit bound = explicit_damping_limit(runner.system());
  EXPECT_NEAR(bound.damping, 11200., 0.);
  EXPECT_NEAR(bound.step, 2. / (11200. * bound.mass_factor), 1e-18);
  const DynamicState& s = runner.initial_state();
  const HalfExplicitStepLimit l =
      half_explicit_step_limit(runner.system(), s.active, 1.1 * bound.step, s.t);
  std::cout << "  explicit damping bound " << bound.step << " s, critical step "
            << l.critical << " s\n";
  EXPECT_LE(l.critical, bound.step);
  EXPECT_GT(l.critical, 0.98 * bound.step);
}

TEST(Robustness, AStepThatDividesTheRunIsKeptBitForBit)
{
  // 0.5 s in steps of 5e-5 s: 10000 steps of exactly the step asked for.
  TimeIntegrationParameters p;
  p.time_step = 5e-5;
  EXPECT_EQ(p.number_of_steps(0.5), 10000u);
  EXPECT_EQ(p.step_for(0.5), 5e-5);
  p.time_step = 0.3; // the probe's case: 2 steps of 0.25 s, not 0.6 s
  EXPECT_EQ(p.number_of_steps(0.5), 2u);
  EXPECT_DOUBLE_EQ(p.step_for(0.5), 0.25);
}

// The run's bound guard counts the entries beyond the span, NaN and infinity
// included, with a vector loop over blocks of eight and a scalar tail. The
// count must be exact for every length (a tail entry within the bound is not
// outside): checked against the plain loop for lengths 0 to 19 and every
// position of a NaN, an infinity and a large entry.
TEST(Robustness, TheBoundGuardCountsEntriesOutsideExactlyForEveryLength)
{
  const double bound = 100.;
  const double specials[] = {std::numeric_limits<double>::quiet_NaN(),
                             -std::numeric_limits<double>::infinity(), -150., 100.};
  for (unsigned int n = 0; n < 20; ++n)
    for (unsigned int where = 0; where <= n; ++where)
      for (const double special : specials)
      {
        dealii::Vector<double> x(n);
        for (unsigned int i = 0; i < n; ++i)
          x(i) = (i % 3 == 0 ? -1. : 1.) * 0.37 * i;
        if (where < n)
          x(where) = special;
        std::size_t expected = 0;
        double largest = 0.;
        for (unsigned int i = 0; i < n; ++i)
        {
          expected += !(std::abs(x(i)) <= bound);
          largest = std::max(largest, std::abs(x(i)));
        }
        EXPECT_EQ(count_outside(x, bound), expected) << "n = " << n << ", at " << where;
        if (std::isfinite(special) || where == n)
          EXPECT_EQ(largest_magnitude(x), largest) << "n = " << n;
        else
          EXPECT_FALSE(std::isfinite(largest_magnitude(x))) << "n = " << n;
      }
}
