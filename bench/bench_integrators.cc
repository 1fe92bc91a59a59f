// Time per step of the integrators on the paper's benchmark (32 m/s), for
// N+1 = 500, 2000, 8000, against simple baselines measured in the same run:
//  - FDM + half-explicit against a fused single-sweep kernel of the same
//    method (bench/fused_half_explicit.h), whose contact force is checked
//    against the library's;
//  - FEM + BDF-2 against one solve with its iteration matrix by the library's
//    banded Cholesky (SparseDirectSolver, twisted factors: the fastest solve we have);
// then the sparse direct solvers (banded Cholesky, UMFPACK, Trilinos KLU) on the
// same BDF-2 iteration matrices.
// Every figure is the fastest of 5 batches (noisy machines).
// Usage: bench_integrators [--half-explicit-only] [steps] [N+1 ...]; prints
// Markdown tables; exit status 1 if the fused kernel's contact force differs
// from the library's.
#include "banded_solve_time.h"
#include "bench_error.h"

#include "fused_half_explicit.h"

#include <pantocat/app/program_parameters.h>
#include <pantocat/lac/sparse_direct_solver.h>
#include <pantocat/pantograph/pantograph_parameters.h>
#include <pantocat/simulation/case_runner.h>
#include <pantocat/space/catenary_discretisation.h>
#include <pantocat/space/smoothed_delta.h>
#include <pantocat/time/time_integrator.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

using namespace pantocat;
using pantocat::bench::FusedContact;
using pantocat::bench::FusedHalfExplicit;
using Clock = std::chrono::steady_clock;

namespace
{
double seconds_since(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

ProgramParameters benchmark(unsigned int n, SpaceMethod method, std::string integrator,
                            double dt)
{
  ProgramParameters p;
  p.discretisation.method = method;
  p.discretisation.n_intervals = n;
  p.time_integration.integrator = integrator;
  p.time_integration.time_step = dt;
  p.time_integration.force_step_size = true;
  return p;
}

/// The machines are noisy: every figure is the fastest of this many batches.
constexpr unsigned int batches = 5;

/// Microseconds per step of the library's integrator (no observers).
double library_step(const ProgramParameters& p, unsigned int steps)
{
  CaseRunner simulation(p.make_case(), {p.output.probe_positions, p.output.energy});
  auto integrator = create_time_integrator(simulation.system(), p.time_integration);
  integrator->initialize(simulation.initial_state());
  integrator->advance(); // start-up (factorisations, Richardson start) not timed
  double best = 1e300;
  const unsigned int per_batch = std::max(1u, steps / batches);
  for (unsigned int b = 0; b < batches; ++b)
  {
    const auto t0 = Clock::now();
    for (unsigned int k = 0; k < per_batch; ++k)
      integrator->advance();
    best = std::min(best, 1e6 * seconds_since(t0) / per_batch);
  }
  return best;
}

/// The library's FDM + half-explicit integrator and the fused kernel on one case.
struct HalfExplicitPair
{
  explicit HalfExplicitPair(const ProgramParameters& p)
      : simulation(p.make_case(), {p.output.probe_positions, p.output.energy}),
        integrator(create_time_integrator(simulation.system(), p.time_integration)),
        kernel(simulation.system(), simulation.initial_state(), contact(p),
               simulation.layout().pantographs.at(0).contact,
               simulation.layout().dropper_indices, p.time_integration.time_step)
  {
    integrator->initialize(simulation.initial_state());
  }

  /// The contact's motion and the grid of @p p for the kernel.
  FusedContact contact(const ProgramParameters& p) const
  {
    const PantographParameters& pantograph = p.pantograph();
    FusedContact c;
    c.initial_position = pantograph.initial_position;
    c.speed = pantograph.speed;
    c.half_width = p.discretisation.load_half_width;
    c.grid_spacing = simulation.discretisation().cell_size();
    return c;
  }

  CaseRunner simulation;
  std::unique_ptr<TimeIntegrator> integrator;
  FusedHalfExplicit kernel;
};

/// The largest difference of the contact forces of library and kernel over some steps.
struct ForceCheck
{
  unsigned int steps = 0;
  double largest_force = 0.;      ///< max |lambda_p| of the library [N]
  double largest_difference = 0.; ///< max |lambda_p(kernel) - lambda_p(library)| [N]
};

/**
 * Runs library and kernel side by side for @p steps steps from the initial
 * state and compares lambda_p(t_n) at every step: the kernel computes the
 * same method, not just the same operation count.
 */
ForceCheck check_kernel(const ProgramParameters& p, const unsigned int steps)
{
  HalfExplicitPair pair(p);
  const unsigned int contact = pair.simulation.layout().pantographs.at(0).contact;
  ForceCheck check;
  check.steps = steps;
  for (unsigned int k = 0; k < steps; ++k)
  {
    pair.integrator->advance();
    pair.kernel.step();
    const double library = pair.integrator->latest().lambda.at(contact);
    check.largest_force = std::max(check.largest_force, std::abs(library));
    check.largest_difference = std::max(check.largest_difference,
                                        std::abs(pair.kernel.contact_force() - library));
  }
  return check;
}

/// Microseconds per step of library and kernel, batches interleaved, the fastest of each.
std::pair<double, double> time_half_explicit(const ProgramParameters& p,
                                             const unsigned int steps)
{
  HalfExplicitPair pair(p);
  pair.integrator->advance(); // start-up not timed
  pair.kernel.step();
  const unsigned int per_batch = std::max(1u, steps / batches);
  double library = 1e300, kernel = 1e300;
  for (unsigned int b = 0; b < batches; ++b)
  {
    auto t0 = Clock::now();
    for (unsigned int k = 0; k < per_batch; ++k)
      pair.integrator->advance();
    library = std::min(library, 1e6 * seconds_since(t0) / per_batch);
    t0 = Clock::now();
    for (unsigned int k = 0; k < per_batch; ++k)
      pair.kernel.step();
    kernel = std::min(kernel, 1e6 * seconds_since(t0) / per_batch);
  }
  volatile double sink = pair.kernel.contact_force();
  (void)sink;
  return {library, kernel};
}

} // namespace

/**
 * The three sparse direct solvers on the same matrix, S = K + c D + c^2 M of
 * FEM + BDF-2 with dt = c dx^2: factorisation [ms], one solve [us], and a
 * whole BDF-2 step of the library with that solver [us].
 */
void compare_linear_solvers(const std::vector<unsigned int>& grids, unsigned int steps)
{
  std::cout << "\n| N+1 | solver | factorise [ms] | solve [us] | FEM+BDF2 step [us] |\n"
            << "|---|---|---|---|---|\n";
  for (const unsigned int n : grids)
  {
    const double scale = 500. / n, dt = 5e-5 * scale * scale, c = 1.5 / dt;
    ProgramParameters p = benchmark(n, SpaceMethod::fem, "bdf2", dt);
    CaseRunner simulation(p.make_case(), {p.output.probe_positions, p.output.energy});
    const SemiDiscreteSystem& sys = simulation.system();
    dealii::SparseMatrix<double> S(*sys.sparsity);
    S.copy_from(sys.stiffness);
    S.add(c, sys.damping);
    S.add(c * c, sys.mass);
    for (const auto type : {LinearSolverType::banded, LinearSolverType::umfpack,
                            LinearSolverType::trilinos_klu})
    {
      SparseDirectSolver solver;
      double factorise = 1e300, solve = 1e300;
      dealii::Vector<double> x(sys.n_dofs());
      for (unsigned int b = 0; b < batches; ++b)
      {
        auto t0 = Clock::now();
        solver.factorize(S, "S", type);
        factorise = std::min(factorise, 1e3 * seconds_since(t0));
        const unsigned int repetitions = 20;
        t0 = Clock::now();
        for (unsigned int r = 0; r < repetitions; ++r)
        {
          x = 1.;
          solver.solve(x);
        }
        solve = std::min(solve, 1e6 * seconds_since(t0) / repetitions);
      }
      p.time_integration.linear_solver = type;
      const double step = library_step(p, std::max(20u, steps / (n / 250)));
      std::cout << std::setprecision(3) << "| " << n << " | " << to_string(type) << " | "
                << factorise << " | " << solve << " | " << step << " |" << std::endl;
    }
  }
}

/// Relative tolerance of the kernel's contact force against the library's.
constexpr double force_tolerance = 1e-6;

/**
 * FDM + half-explicit against the fused kernel: time per step and ratio, then
 * the check of the kernel's contact force. Returns false if the check fails.
 */
bool half_explicit_table(const std::vector<unsigned int>& grids, const unsigned int steps)
{
  std::cout << "| N+1 | FDM+HE [us/step] | fused kernel [us/step] | ratio | kernel [ns "
               "per unknown and step] |\n|---|---|---|---|---|\n";
  for (const unsigned int n : grids)
  {
    // dt = c dx^2 as in Sec. 5.2, scaled from the paper's 5e-5 s at N+1 = 500.
    const double scale = 500. / n, dt = 5e-5 * scale * scale;
    const auto [library, kernel] =
        time_half_explicit(benchmark(n, SpaceMethod::fdm, "half-explicit", dt), steps);
    std::cout << std::setprecision(3) << "| " << n << " | " << library << " | " << kernel
              << " | " << library / kernel << " | " << 1e3 * kernel / (2. * n) << " |"
              << std::endl;
  }
  // The check: 4400 steps at N+1 = 500 (x_p from 2 to 13 m, under dropper 1 at
  // 5.5 m), and 1000 steps on the finer grids.
  std::cout << "\n| N+1 | steps compared | max abs(lambda_p) [N] | max abs(kernel - "
               "library) [N] | relative |\n|---|---|---|---|---|\n";
  bool passed = true;
  for (const unsigned int n : grids)
  {
    const double scale = 500. / n, dt = 5e-5 * scale * scale;
    const ForceCheck c = check_kernel(benchmark(n, SpaceMethod::fdm, "half-explicit", dt),
                                      n <= 500 ? 4400 : 1000);
    const double relative = c.largest_difference / c.largest_force;
    passed = passed && relative < force_tolerance;
    std::cout << std::setprecision(4) << "| " << n << " | " << c.steps << " | "
              << c.largest_force << " | " << std::setprecision(2) << c.largest_difference
              << " | " << relative << " |" << std::endl;
  }
  std::cout << "kernel check (relative difference below " << force_tolerance
            << "): " << (passed ? "passed" : "FAILED") << std::endl;
  return passed;
}

/// FEM + BDF-2 against one solve with its iteration matrix by the library's
/// banded Cholesky (bench::banded_solve_microseconds), and FDM + BDF-2.
void bdf2_table(const std::vector<unsigned int>& grids, const unsigned int steps)
{
  std::cout << "\n| N+1 | FEM+BDF2 [us/step] | banded solve [us] | ratio | FDM+BDF2 "
               "[us/step] |\n|---|---|---|---|---|\n";
  for (const unsigned int n : grids)
  {
    const double scale = 500. / n, dt = 5e-5 * scale * scale;
    const unsigned int bdf_steps = std::max(20u, steps / (n / 250));
    const ProgramParameters fem = benchmark(n, SpaceMethod::fem, "bdf2", dt);
    const double bdf = library_step(fem, bdf_steps);
    const double banded = bench::banded_solve_microseconds(fem, 5, 500);
    const double fdm_bdf =
        library_step(benchmark(n, SpaceMethod::fdm, "bdf2", dt), bdf_steps);
    std::cout << std::setprecision(3) << "| " << n << " | " << bdf << " | " << banded
              << " | " << bdf / banded << " | " << fdm_bdf << " |" << std::endl;
  }
}

int main(int argc, char** argv)
try
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  dealii::MultithreadInfo::set_thread_limit(1); // as pantocat-fem does
  bool half_explicit_only = false;
  std::vector<std::string> args;
  for (int i = 1; i < argc; ++i)
  {
    if (std::string(argv[i]) == "--half-explicit-only")
      half_explicit_only = true;
    else
      args.push_back(argv[i]);
  }
  const unsigned int steps = args.size() > 0 ? std::stoi(args[0]) : 2000;
  std::vector<unsigned int> grids;
  for (std::size_t i = 1; i < args.size(); ++i)
    grids.push_back(std::stoi(args[i]));
  if (grids.empty())
    grids = {500, 2000, 8000};

  const bool passed = half_explicit_table(grids, steps);
  if (!half_explicit_only)
  {
    bdf2_table(grids, steps);
    compare_linear_solvers(grids, steps / 4);
  }
  return passed ? 0 : 1;
}
catch (const std::exception& e)
{
  return report_bench_error("bench_integrators", e);
}
