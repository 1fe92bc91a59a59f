// The step limit of the half-explicit method with the moving contact
// (doc/stability.md): for each step dt of a list, the growth per step of
// perturbations (growth_per_step) with the contact moving as in the run and
// frozen at positions xi = 0, 1/4, 1/2, 3/4 of a cell, and, with --run, the
// outcome of the run itself (completed, or the step a guard stopped it at).
// Usage: bench_step_limit file.prm [--set Sub/Entry=value ...] [--steps K]
//        [--run] [--limit] dt/(2/omega_max) ...
#include "bench_error.h"

#include <pantocat/analysis/half_explicit_step_map.h>
#include <pantocat/analysis/stability_limit.h>
#include <pantocat/app/program_parameters.h>
#include <pantocat/simulation/case_runner.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

using namespace pantocat;
using Clock = std::chrono::steady_clock;

int main(int argc, char** argv)
try
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  if (argc < 2)
  {
    std::cerr << "usage: bench_step_limit file.prm [--set S/E=v ...] [--steps K] [--run] "
                 "[--limit] ratio ...\n";
    return 2;
  }
  std::vector<std::string> overrides;
  std::vector<double> ratios;
  unsigned int steps = 2000;
  bool run = false, limit = false;
  unsigned int windows = 0;
  for (int i = 2; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--set" && i + 1 < argc)
      overrides.push_back(argv[++i]);
    else if (a == "--steps" && i + 1 < argc)
      steps = std::stoul(argv[++i]);
    else if (a == "--run")
      run = true;
    else if (a == "--windows" && i + 1 < argc)
      windows = std::stoul(argv[++i]);
    else if (a == "--limit")
      limit = true;
    else
      ratios.push_back(std::stod(a));
  }
  overrides.push_back("Time integration/Force step size=true");
  dealii::ParameterHandler prm;
  read_program_parameters(prm, argv[1], overrides);
  ProgramParameters p;
  p.parse_parameters(prm);
  const Case base = p.make_case();
  const CaseRunner probe(base);
  const double unconstrained = probe.explicit_stability_limit();
  const auto& pan = base.scene.pantographs[0].parameters;
  const double h = base.catenary.length() / base.discretisation.n_intervals;
  // The first node at or after the initial position, and the times the
  // contact is at xi of the cell after it.
  const double x0 = pan.initial_position, speed = pan.speed;
  const double node = std::ceil(x0 / h - 1e-9) * h;
  std::cout << "# " << argv[1] << ", N+1 = " << base.discretisation.n_intervals
            << ", h = " << h << " m, v_p = " << speed
            << " m/s, 2/omega_max = " << std::setprecision(4) << unconstrained
            << " s, steps = " << steps << "\n";
  if (limit)
  {
    const auto t0 = Clock::now();
    const auto& s0 = probe.initial_state();
    const HalfExplicitStepLimit l =
        half_explicit_step_limit(probe.system(), s0.active, unconstrained, s0.t);
    std::cout << "# critical step " << l.critical << " s = " << l.critical / unconstrained
              << " x 2/omega_max (unstable: " << l.unstable << " s, growth "
              << std::setprecision(6) << l.growth_unstable << std::setprecision(4)
              << "), allowed " << l.allowed << " s, " << l.tests << " power iterations, "
              << std::chrono::duration<double>(Clock::now() - t0).count() << " s\n";
  }
  std::cout << "| dt/(2/omega_max) | dt [s] | growth, moving | frozen xi = 0 | 1/4 | 1/2 "
               "| 3/4 | estimate [s] | run |\n";
  for (const double ratio : ratios)
  {
    const double dt = ratio * unconstrained;
    Case c = base;
    c.time_integration.time_step = dt;
    CaseRunner runner(c);
    const auto& s = runner.system();
    const auto& active = runner.initial_state().active;
    const auto t0 = Clock::now();
    const double moving =
        growth_per_step(s, active, runner.time_step(), runner.initial_state().t, steps);
    const double cost = std::chrono::duration<double>(Clock::now() - t0).count();
    std::cout << "| " << std::setprecision(4) << ratio << " | " << runner.time_step()
              << " | " << std::setprecision(6) << moving;
    for (const double xi : {0., 0.25, 0.5, 0.75})
    {
      const double tf = (node + xi * h - x0) / speed;
      std::cout << " | "
                << growth_per_step(s, active, runner.time_step(), tf, steps,
                                   ContactRows::frozen);
    }
    std::cout << " | " << std::setprecision(3) << cost << " | ";
    for (unsigned int j = 0; j < windows; ++j)
    {
      const double tj = runner.initial_state().t + j * c.end_time() / windows;
      std::cout << "x_p " << x0 + speed * tj << ": " << std::setprecision(6)
                << growth_per_step(s, active, runner.time_step(), tj, steps) << "; "
                << std::setprecision(3);
    }
    if (run)
    {
      try
      {
        const auto r = runner.run({});
        std::cout << "completed (" << r.integrator.steps << " steps)";
      }
      catch (const std::exception& e)
      {
        std::cout << e.what();
      }
    }
    std::cout << " |" << std::endl;
  }
}
catch (const std::exception& e)
{
  return report_bench_error("bench_step_limit", e);
}
