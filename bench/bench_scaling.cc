// Cost per step against the number of unknowns n (issue 16: linear in N + m up
// to 1e5 unknowns). The paper's benchmark (prm/benchmark-32.prm: 20 m spans,
// the two droppers of each span, the two-mass pantograph at 32 m/s) repeated
// over s spans with the grid spacing fixed at the paper's dx = 0.04 m
// (N+1 = 500 s), so that n and the number m of constraints both grow with s.
// For FDM + half-explicit, FEM + half-explicit, FEM + BDF-2, FEM +
// generalized-alpha, FDM + BDF-2 and FDM + generalized-alpha: the time per
// step (integrator alone, start-up not
// timed, the fastest of 3 batches of about 0.1 s each), and the time per step
// and unknown. Steps: dt = 5e-5 s, and half the explicit stability limit for
// FEM + half-explicit (the limit does not depend on s at a fixed h).
// Usage: bench_scaling [spans ...] [--only=fem+half-explicit] (one column)
// (default 1 3 10 30 45 66 100); prints a Markdown table.
#include "bench_error.h"

#include <pantocat/app/program_parameters.h>
#include <pantocat/simulation/case_runner.h>
#include <pantocat/time/time_integrator.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/parameter_handler.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace pantocat;
using Clock = std::chrono::steady_clock;

namespace
{
/// One column of the table: a discretisation and an integrator.
struct Column
{
  std::string method, integrator;
};

/// prm/benchmark-32.prm over @p spans spans of 20 m with dx = 0.04 m.
ProgramParameters benchmark_spans(const unsigned int spans, const Column& c,
                                  const double dt)
{
  const std::vector<std::string> overrides = {
      "Catenary/Number of spans=" + std::to_string(spans),
      "Pantograph/Final position=" + std::to_string(20 * spans - 2),
      "Discretisation/Method=" + c.method,
      "Discretisation/Number of intervals=" + std::to_string(500 * spans),
      "Time integration/Integrator=" + c.integrator,
      "Time integration/Time step=" + std::to_string(dt)};
  dealii::ParameterHandler prm;
  read_program_parameters(prm, PANTOCAT_SOURCE_DIR "/prm/benchmark-32.prm", overrides);
  ProgramParameters p;
  p.parse_parameters(prm);
  p.time_integration.time_step = dt; // to_string rounds to 6 decimals
  p.time_integration.force_step_size = true;
  return p;
}

/// The measurement of one case.
struct StepCost
{
  unsigned int unknowns = 0, constraints = 0;
  double microseconds = 0.; ///< per step
};

/// Time per step of the integrator alone: 3 batches of about 0.1 s, the fastest.
StepCost step_cost(const ProgramParameters& p)
{
  CaseRunner simulation(p.make_case(), {p.output.probe_positions, p.output.energy});
  auto integrator = create_time_integrator(simulation.system(), p.time_integration);
  integrator->initialize(simulation.initial_state());
  // Start-up not timed: the first steps factorise and form the columns of
  // the fixed constraints (for BDF-2 on 10^5 unknowns, about a second). The
  // step after them sizes the batches.
  integrator->advance();
  integrator->advance();
  auto t0 = Clock::now();
  integrator->advance();
  const double first = std::chrono::duration<double>(Clock::now() - t0).count();
  const unsigned int per_batch = std::clamp<unsigned int>(0.1 / first, 3, 20000);
  StepCost cost;
  cost.unknowns = simulation.system().n_dofs();
  cost.constraints = simulation.system().n_constraints();
  cost.microseconds = 1e300;
  for (unsigned int b = 0; b < 3; ++b)
  {
    t0 = Clock::now();
    for (unsigned int k = 0; k < per_batch; ++k)
      integrator->advance();
    cost.microseconds = std::min(
        cost.microseconds,
        1e6 * std::chrono::duration<double>(Clock::now() - t0).count() / per_batch);
  }
  return cost;
}

/// Half the explicit stability limit of @p c on the one-span grid (dx = 0.04 m).
double half_stability_limit(const Column& c)
{
  const ProgramParameters p = benchmark_spans(1, c, 5e-5);
  CaseRunner simulation(p.make_case(), {p.output.probe_positions, p.output.energy});
  return 0.5 * simulation.explicit_stability_limit();
}
} // namespace

int main(int argc, char** argv)
try
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  dealii::MultithreadInfo::set_thread_limit(1); // as pantocat-fem does
  std::vector<unsigned int> spans;
  std::string only; // --only=fem+bdf2 : one column
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]).rfind("--only=", 0) == 0)
      only = std::string(argv[i]).substr(7);
    else
      spans.push_back(std::atoi(argv[i]));
  if (spans.empty())
    spans = {1, 3, 10, 30, 45, 66, 100};
  std::vector<Column> columns = {{"fdm", "half-explicit"}, {"fem", "half-explicit"},
                                 {"fem", "bdf2"},          {"fem", "generalized-alpha"},
                                 {"fdm", "bdf2"},          {"fdm", "generalized-alpha"}};
  if (!only.empty())
    columns.erase(std::remove_if(columns.begin(), columns.end(),
                                 [&](const Column& c)
                                 { return c.method + "+" + c.integrator != only; }),
                  columns.end());
  if (columns.empty())
    throw std::invalid_argument("--only=" + only +
                                ": not a column (fdm+half-explicit, fem+half-explicit, "
                                "fem+bdf2, fem+generalized-alpha, fdm+bdf2, "
                                "fdm+generalized-alpha)");
  std::vector<double> steps;
  for (const Column& c : columns)
    steps.push_back(c.method == "fem" && c.integrator == "half-explicit"
                        ? half_stability_limit(c)
                        : 5e-5);
  std::cout << "| spans |";
  for (const Column& c : columns)
    std::cout << ' ' << c.method << " + " << c.integrator
              << ": n | m | us/step | ns/(n step) |";
  std::cout << "\n|---|";
  for (std::size_t k = 0; k < columns.size(); ++k)
    std::cout << "---|---|---|---|";
  std::cout << '\n';
  for (const unsigned int s : spans)
  {
    std::cout << "| " << s << " |";
    for (std::size_t k = 0; k < columns.size(); ++k)
    {
      const StepCost c = step_cost(benchmark_spans(s, columns[k], steps[k]));
      std::cout << ' ' << c.unknowns << " | " << c.constraints << " | "
                << std::setprecision(3) << c.microseconds << " | "
                << 1e3 * c.microseconds / c.unknowns << " |" << std::flush;
    }
    std::cout << '\n';
  }
}
catch (const std::exception& e)
{
  return report_bench_error("bench_scaling", e);
}
