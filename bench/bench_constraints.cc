// Cost per step against the number m of fixed constraints (issue 16): one
// 100 m span, FDM with N+1 = 2500 intervals (dx = 0.04 m as in the paper's
// benchmark) or FEM with N+1 = 500 (Hermite beam, h = 0.2 m), the benchmark's wires and
// pantograph at 32 m/s, dt = 5e-5 s, m bilateral droppers evenly spaced (0.95 m long), m
// = 0 (Droppers = absent), 2, 10, 40, 100, 200. Each integrator's time per step (no
// observers, start-up not timed; the cases of a column run their batches in
// turns, the fastest of 10 batches counts), and its ratio to
// the same grid without droppers: the target is 1.5 for m up to 200.
// Columns: FDM and FEM with the half-explicit method, BDF-2 and
// generalized-alpha; then one banded solve with the FEM BDF-2 matrix S (the
// reference of the implicit methods' target, 2.5 solves per step), and per m
// one solve of the constrained system [S G_F^T; G_F 0] (S solve, Schur
// complement, truncated columns), a lower bound of a BDF-2 step (the
// library's right-hand side and solve, the two corrections, one minimal
// update pass) and the FEM implicit steps in both units.
// Usage: bench_constraints [steps] [m ...]
// [--only=fem+bdf2] (one column) [--no-baseline] (skip m = 0, e.g. to profile one m)
// [--span=L] (a span of L metres instead of 100, the same h and dx: with L = 1000
// and m = 200 the constraints are 5 m apart, the density of a real section such
// as S55's 100 droppers and steady arms in 550 m)
#include "banded_solve_time.h"
#include "bench_error.h"

#include <pantocat/app/program_parameters.h>
#include <pantocat/lac/sparse_direct_solver.h>
#include <pantocat/simulation/case_runner.h>
#include <pantocat/constrained_fast/iteration_matrix.h>
#include <pantocat/time/time_integrator.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/parameter_handler.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <vector>

using namespace pantocat;
using Clock = std::chrono::steady_clock;

namespace
{
constexpr unsigned int batches = 10;

/// The case: prm/benchmark-32.prm on a 100 m span with m droppers.
ProgramParameters span_with_droppers(const unsigned int m, const std::string& method,
                                     const std::string& integrator,
                                     const unsigned int span = 100)
{
  // FEM beams need dt ~ h^2 with the half-explicit method: h = 0.2 m there
  // (2/omega_max = 1.3e-4 s), dt = 5e-5 s for all.
  const std::string intervals = std::to_string((method == "fem" ? 5 : 25) * span);
  std::ostringstream positions, lengths;
  for (unsigned int j = 0; j < m; ++j)
  {
    positions << (j ? "," : "") << span * (j + 0.5) / m;
    lengths << (j ? "," : "") << 0.95;
  }
  std::vector<std::string> overrides = {
      "Catenary/Span=" + std::to_string(span),
      "Pantograph/Final position=" + std::to_string(span - 2),
      "Discretisation/Method=" + method,
      "Discretisation/Number of intervals=" + intervals,
      "Time integration/Integrator=" + integrator,
      "Time integration/Time step=5e-5",
      "Scene/Droppers=" + std::string(m ? "bilateral" : "absent")};
  if (m == 0)
    overrides.push_back("Scene/Clamp and dropper masses=false");
  else
  {
    overrides.push_back("Catenary/Droppers/Positions=" + positions.str());
    overrides.push_back("Catenary/Droppers/Lengths=" + lengths.str());
  }
  dealii::ParameterHandler prm;
  read_program_parameters(prm, PANTOCAT_SOURCE_DIR "/prm/benchmark-32.prm", overrides);
  ProgramParameters p;
  p.parse_parameters(prm);
  p.time_integration.force_step_size = true;
  return p;
}

/**
 * Microseconds per step of the integrator alone for each case of @p cases:
 * all integrators are made first, then their batches run in turns (case 1,
 * case 2, ..., case 1, ...), and each case's fastest batch counts. A machine
 * whose speed drifts then slows every case of a turn alike, and the ratios
 * to m = 0 are measured side by side.
 */
std::vector<double> step_times(const std::vector<ProgramParameters>& cases,
                               const unsigned int steps)
{
  struct Running
  {
    std::unique_ptr<CaseRunner> simulation;
    std::unique_ptr<TimeIntegrator> integrator;
  };
  std::vector<Running> running;
  for (const ProgramParameters& p : cases)
  {
    Running r;
    r.simulation = std::make_unique<CaseRunner>(
        p.make_case(), Measurements{p.output.probe_positions, p.output.energy});
    r.integrator = create_time_integrator(r.simulation->system(), p.time_integration);
    r.integrator->initialize(r.simulation->initial_state());
    r.integrator->advance(); // start-up not timed
    running.push_back(std::move(r));
  }
  std::vector<double> best(cases.size(), 1e300);
  const unsigned int per_batch = std::max(1u, steps / batches);
  for (unsigned int b = 0; b < batches; ++b)
    for (std::size_t c = 0; c < running.size(); ++c)
    {
      const auto t0 = Clock::now();
      for (unsigned int k = 0; k < per_batch; ++k)
        running[c].integrator->advance();
      best[c] = std::min(best[c],
                         1e6 * std::chrono::duration<double>(Clock::now() - t0).count() /
                             per_batch);
    }
  return best;
}

struct Column
{
  std::string method, integrator;
  unsigned int steps;
};

/**
 * The FEM implicit steps in banded solves: per m, one solve of the
 * constrained system (bench::constrained_solve_microseconds(), the same
 * grid with the m droppers), a lower bound of a BDF-2 step from the
 * library's kernels (bench::bdf2_step_floor_microseconds()) in solves with
 * S, and each FEM BDF-2 / generalized-alpha step divided by one constrained
 * solve and by one solve with S alone (@p solve_with_S).
 */
void print_steps_in_solves(const std::vector<unsigned int>& ms,
                           const std::vector<Column>& columns,
                           const std::vector<std::vector<double>>& times,
                           const double solve_with_S, const unsigned int span)
{
  std::vector<std::size_t> implicit;
  for (std::size_t k = 0; k < columns.size(); ++k)
    if (columns[k].method == "fem" && columns[k].integrator != "half-explicit")
      implicit.push_back(k);
  if (implicit.empty())
    return;
  std::cout
      << "\n| m | one constrained solve [us] | BDF-2 step floor [us] | in S solves |";
  for (const std::size_t k : implicit)
    std::cout << " fem + " << columns[k].integrator
              << " in S solves | in constrained solves |";
  std::cout << "\n|---|---|---|---|";
  for (std::size_t k = 0; k < implicit.size(); ++k)
    std::cout << "---|---|";
  std::cout << '\n';
  for (std::size_t r = 0; r < ms.size(); ++r)
  {
    const double solve = ms[r] == 0 ? solve_with_S
                                    : bench::constrained_solve_microseconds(
                                          span_with_droppers(ms[r], "fem", "bdf2", span));
    const double floor = bench::bdf2_step_floor_microseconds(
        span_with_droppers(ms[r], "fem", "bdf2", span));
    std::cout << "| " << ms[r] << " | " << std::setprecision(3) << solve << " | " << floor
              << " | " << floor / solve_with_S << " |";
    for (const std::size_t k : implicit)
      std::cout << ' ' << times[k][r] / solve_with_S << " | " << times[k][r] / solve
                << " |";
    std::cout << '\n';
  }
}
} // namespace

int main(int argc, char** argv)
try
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  dealii::MultithreadInfo::set_thread_limit(1); // as pantocat-fem does
  const unsigned int steps = argc > 1 ? std::atoi(argv[1]) : 1000;
  std::vector<unsigned int> counts;
  std::string only; // --only=fem+bdf2 : one column
  bool baseline = true;
  unsigned int span = 100; // --span=1000 : the constraints of a real section's density
  for (int i = 2; i < argc; ++i)
    if (std::string(argv[i]) == "--no-baseline")
      baseline = false;
    else if (std::string(argv[i]).rfind("--span=", 0) == 0)
      span = std::atoi(argv[i] + 7);
    else if (std::string(argv[i]).rfind("--only=", 0) == 0)
      only = std::string(argv[i]).substr(7);
    else
      counts.push_back(std::atoi(argv[i]));
  if (counts.empty())
    counts = {2, 10, 40, 100, 200};
  std::vector<Column> columns = {
      {"fdm", "half-explicit", steps}, {"fem", "half-explicit", steps / 2},
      {"fdm", "bdf2", steps / 10},     {"fdm", "generalized-alpha", steps / 10},
      {"fem", "bdf2", steps / 10},     {"fem", "generalized-alpha", steps / 10}};
  if (!only.empty())
    columns.erase(std::remove_if(columns.begin(), columns.end(),
                                 [&](const Column& c)
                                 { return c.method + "+" + c.integrator != only; }),
                  columns.end());
  std::cout << "| m |";
  for (const Column& c : columns)
    std::cout << ' ' << c.method << " + " << c.integrator << " [us/step] | ratio |";
  std::cout << "\n|---|";
  for (std::size_t k = 0; k < columns.size(); ++k)
    std::cout << "---|---|";
  std::cout << '\n';
  // Each column's cases (m = 0 first) in turns; the table row by row.
  std::vector<unsigned int> ms = counts;
  if (baseline)
    ms.insert(ms.begin(), 0);
  std::vector<std::vector<double>> times; // [column][case]
  for (const Column& c : columns)
  {
    std::vector<ProgramParameters> cases;
    for (const unsigned int m : ms)
      cases.push_back(span_with_droppers(m, c.method, c.integrator, span));
    times.push_back(step_times(cases, c.steps));
  }
  for (std::size_t r = 0; r < ms.size(); ++r)
  {
    std::cout << "| " << ms[r] << " |";
    for (std::size_t k = 0; k < columns.size(); ++k)
    {
      const double t = times[k][r];
      std::cout << ' ' << std::setprecision(3) << t << " | ";
      if (baseline)
        std::cout << t / times[k][0];
      else
        std::cout << '-';
      std::cout << " |";
    }
    std::cout << '\n';
  }
  if (!baseline)
    return 0;
  const double solve_with_S =
      bench::banded_solve_microseconds(span_with_droppers(0, "fem", "bdf2", span));
  std::cout << "\nOne banded solve with the FEM BDF-2 matrix of this grid: "
            << std::setprecision(3) << solve_with_S << " us\n";
  print_steps_in_solves(ms, columns, times, solve_with_S, span);
}
catch (const std::exception& e)
{
  return report_bench_error("bench_constraints", e);
}
