// Cost of the run's observers on the paper's 32 m/s benchmark (FDM +
// half-explicit, N+1 = 500, 10^4 steps): the time loop with no observer, with
// the observers every run has (time_series.csv, run statistics, contact-force
// statistics with the dropper uplift), and with ParaView frames added.
// Every figure is the fastest of the rounds over all cases; ratios to the loop
// without observers and to the integrator alone.
// Usage: bench_output [rounds] (default 5); prints a table (Markdown).
//        bench_output rounds --only=K runs only case K (0 = none, 1 = time series
//        + run statistics, 2 = + contact-force statistics, ...) for a profile.
#include "bench_error.h"

#include <pantocat/app/program_parameters.h>
#include <pantocat/io/time_series_writer.h>
#include <pantocat/io/vtu_time_series_writer.h>
#include <pantocat/simulation/case_runner.h>
#include <pantocat/simulation/contact_statistics.h>
#include <pantocat/simulation/run_statistics.h>
#include <pantocat/time/time_integrator.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace pantocat;

namespace
{
enum class Observers
{
  none,
  before_issue_8, ///< time series and RunStatistics
  every_run,      ///< + ContactStatistics (observe_state every step)
  vtu_50ms,       ///< + VTU frames every 50 ms (11 frames)
  vtu_5ms         ///< + VTU frames every 5 ms (101 frames)
};

/// Seconds of the integrator alone over the run's steps (no time points, guards
/// or observers): the baseline of the time loop (issue 16: within 1.5 times).
double integrator_alone(const ProgramParameters& p)
{
  CaseRunner simulation(p.make_case(), {p.output.probe_positions, p.output.energy});
  auto integrator = create_time_integrator(simulation.system(), p.time_integration);
  integrator->initialize(simulation.initial_state());
  const unsigned long steps = simulation.number_of_steps();
  const auto t0 = std::chrono::steady_clock::now();
  for (unsigned long n = 0; n < steps; ++n)
    integrator->advance();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Seconds of the time loop (CaseRunner::run) with the given observers.
double time_loop(const ProgramParameters& p, const Observers which)
{
  const std::string dir = "bench_output_files";
  std::filesystem::create_directories(dir);
  CaseRunner simulation(p.make_case(), {p.output.probe_positions, p.output.energy});
  TimeSeriesWriter series(dir + "/time_series.csv", 1);
  RunStatistics stats;
  ContactStatistics contact(p.statistics, simulation.discretisation(),
                            simulation.system());
  VtuTimeSeriesWriter vtu(dir, which == Observers::vtu_5ms ? 0.005 : 0.05,
                          p.time_integration.time_step, 4, simulation.discretisation(),
                          simulation.system());
  std::vector<SimulationObserver*> observers;
  if (which != Observers::none)
    observers = {&series, &stats};
  if (which >= Observers::every_run)
    observers.push_back(&contact);
  if (which >= Observers::vtu_50ms)
    observers.push_back(&vtu);
  const double seconds = simulation.run(observers).time_loop_seconds;
  std::filesystem::remove_all(dir);
  return seconds;
}
} // namespace

int main(int argc, char** argv)
try
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  dealii::MultithreadInfo::set_thread_limit(1); // as pantocat-fem does
  const unsigned int rounds = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  const std::string only_flag = "--only=";
  const bool only_given = argc > 2 && std::string(argv[2]).rfind(only_flag, 0) == 0;
  const int only = only_given ? std::atoi(argv[2] + only_flag.size()) : -1;
  ProgramParameters p;
  p.discretisation.method = SpaceMethod::fdm;
  const std::pair<Observers, const char*> cases[] = {
      {Observers::none, "none"},
      {Observers::before_issue_8, "time series + run statistics"},
      {Observers::every_run, "+ contact-force statistics and uplift (every run)"},
      {Observers::vtu_50ms, "+ VTU every 50 ms (11 frames)"},
      {Observers::vtu_5ms, "+ VTU every 5 ms (101 frames)"}};
  if (only_given && (only < 0 || only >= static_cast<int>(std::size(cases))))
    throw std::invalid_argument("--only=" + std::to_string(only) +
                                ": no such case (0 to " +
                                std::to_string(std::size(cases) - 1) + ")");
  // Rounds over all cases, the fastest of the rounds per case: a busy spell of the
  // machine hits every case alike, so the ratios hold.
  double alone = 1e300;
  std::vector<double> best(std::size(cases), 1e300);
  for (unsigned int run = 0; run < rounds; ++run)
  {
    if (only < 0)
      alone = std::min(alone, integrator_alone(p));
    for (std::size_t k = 0; k < std::size(cases); ++k)
      if (only < 0 || static_cast<std::size_t>(only) == k)
        best[k] = std::min(best[k], time_loop(p, cases[k].first));
  }
  if (only >= 0)
  {
    std::cout << cases[only].second << ": " << best[only] << " s\n";
    return 0;
  }
  std::cout << "| observers | time loop [s] | ratio to none | ratio to the integrator "
               "alone |\n|---|---|---|---|\n";
  std::cout << "| integrator alone (no time points, guards) | " << std::setprecision(3)
            << alone << " | - | 1 |\n";
  for (std::size_t k = 0; k < std::size(cases); ++k)
    std::cout << "| " << cases[k].second << " | " << std::setprecision(3) << best[k]
              << " | " << best[k] / best[0] << " | " << best[k] / alone << " |\n";
}
catch (const std::exception& e)
{
  return report_bench_error("bench_output", e);
}
