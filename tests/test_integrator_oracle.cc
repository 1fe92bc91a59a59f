// The oracle of the constrained linear algebra: every registered integrator
// whose linear algebra is ConstrainedOperator's (IntegratorEntry::
// create_with_linear_algebra) runs the paper's cases twice, with the fast and
// with the reference implementation, step by step side by side; states,
// multipliers, impulses and active sets agree at every step (1e-10 relative:
// the fast implementation's truncations are below 1e-15 of each column and
// entry, and round-off of the two factorisations, banded Cholesky against
// UMFPACK, stays near 1e-13 over a run of thousands of steps).
#include <pantocat/simulation/case_runner.h>
#include <pantocat/time/integrator_registry.h>

#include "support/case_files.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>

using namespace pantocat;

namespace
{
/// max |a - b| / max |b| (0 if both are zero).
template <typename Vector>
double relative_difference(const Vector& a, const Vector& b)
{
  double worst = 0., scale = 0.;
  for (std::size_t i = 0; i < b.size(); ++i)
  {
    worst = std::max(worst, std::abs(a[i] - b[i]));
    scale = std::max(scale, std::abs(b[i]));
  }
  return scale > 0. ? worst / scale : worst;
}

/// The largest differences of a run, and what it saw.
struct Agreement
{
  double q = 0., v = 0., lambda = 0., impulse = 0.;
  unsigned long steps = 0, switches = 0, impacts = 0;
  bool same_active_sets = true;
};

/// @p c run with @p entry, fast and reference side by side.
Agreement run_side_by_side(const Case& c, const IntegratorEntry& entry)
{
  const CaseRunner runner(c);
  TimeIntegrationParameters p = runner.case_data().time_integration;
  p.integrator = entry.name;
  std::unique_ptr<TimeIntegrator> fast =
      entry.create_with_linear_algebra(runner.system(), p, LinearAlgebra::fast);
  std::unique_ptr<TimeIntegrator> reference =
      entry.create_with_linear_algebra(runner.system(), p, LinearAlgebra::reference);
  fast->initialize(runner.initial_state());
  reference->initialize(runner.initial_state());
  Agreement a;
  std::vector<bool> previous = runner.initial_state().active;
  for (unsigned long n = 0; n < runner.number_of_steps(); ++n)
  {
    fast->advance();
    reference->advance();
    const DynamicState &x = fast->latest(), &y = reference->latest();
    a.q = std::max(a.q, relative_difference(x.q, y.q));
    a.v = std::max(a.v, relative_difference(x.v, y.v));
    a.lambda = std::max(a.lambda, relative_difference(x.lambda, y.lambda));
    if (!y.impulse.empty() || !x.impulse.empty())
    {
      ++a.impacts;
      a.impulse = x.impulse.size() == y.impulse.size()
                      ? std::max(a.impulse, relative_difference(x.impulse, y.impulse))
                      : INFINITY;
    }
    a.same_active_sets = a.same_active_sets && x.active == y.active;
    a.switches += x.active != previous;
    previous = x.active;
    ++a.steps;
  }
  return a;
}

/// Runs @p file (with @p overrides) with every integrator on the switch.
void check_case(const std::string& file, const std::vector<std::string>& overrides,
                const unsigned long least_switches = 0)
{
  std::filesystem::current_path(PANTOCAT_SOURCE_DIR); // prm includes
  const Case c = read_case(source_file(file), overrides).make_case();
  unsigned int integrators = 0;
  for (const IntegratorEntry& entry : registered_integrators())
  {
    if (!entry.create_with_linear_algebra)
      continue;
    ++integrators;
    SCOPED_TRACE(file + " with " + entry.name);
    const Agreement a = run_side_by_side(c, entry);
    std::cout << "[ oracle   ] " << file << ", " << entry.name << ": " << a.steps
              << " steps, " << a.switches << " switching, " << a.impacts
              << " with impacts; max relative difference q " << a.q << ", v " << a.v
              << ", lambda " << a.lambda << ", impulse " << a.impulse << "\n";
    EXPECT_TRUE(a.same_active_sets);
    EXPECT_LT(a.q, 1e-10);
    EXPECT_LT(a.v, 1e-10);
    EXPECT_LT(a.lambda, 1e-10);
    EXPECT_LT(a.impulse, 1e-10);
    // The case exercises what it is chosen for (the switches of the
    // unilateral constraints at 48 m/s).
    EXPECT_GE(a.switches, least_switches);
  }
  EXPECT_GE(integrators, 1u); // generalized-alpha at least
}
} // namespace

TEST(IntegratorOracle, Benchmark32FdmAndFem)
{
  // Sec. 6 at 32 m/s, the first 0.1 s (x_p from 2 to 5.2 m: droppers 1 and 2).
  for (const char* method : {"fdm", "fem"})
    check_case("prm/benchmark-32.prm",
               {"Discretisation/Method=" + std::string(method),
                "Pantograph/Final position=5.2"});
}

TEST(IntegratorOracle, Benchmark48FdmAndFemThroughTheSlackDropper)
{
  // Sec. 6 at 48 m/s to t = 0.27 s: dropper 2 slackens at about 0.254 s and
  // re-tensions with an impact at about 0.2605 s.
  for (const char* method : {"fdm", "fem"})
    check_case("prm/benchmark-48.prm",
               {"Discretisation/Method=" + std::string(method),
                "Pantograph/Final position=14.96"},
               2);
}

TEST(IntegratorOracle, PaperFig3Span)
{
  // The 65 m span of Fig. 3 (FDM, 7 designed droppers), the first 0.05 s.
  check_case("prm/catenary/paper-fig3.prm", {"Pantograph/Final position=3.6"});
}

TEST(IntegratorOracle, SectionS55)
{
  // S55 (FEM, 90 elastic droppers, 9 steady arms, penalty contact), the
  // first 10 m of the section (0.11 s at 320 km/h).
  check_case("prm/catenary/section-s55.prm", {"Pantograph/Final position=10"});
}

TEST(IntegratorOracle, SectionS55WithTwoPantographs)
{
  // Two moving contacts 200 m apart in the section, 5 m of travel.
  check_case("prm/catenary/section-s55-two-pantographs.prm",
             {"Pantograph/Final position=205"});
}
