#pragma once

#include <pantocat/app/program_parameters.h>
#include <pantocat/lac/sparse_direct_solver.h>
#include <pantocat/simulation/case_runner.h>
#include <pantocat/time/iteration_matrix.h>

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <chrono>

namespace pantocat::bench
{
/**
 * Microseconds of one solve with the BDF-2 iteration matrix S = K + c D +
 * c^2 M (c = 1.5/dt) of the case @p p by the library's banded Cholesky
 * (SparseDirectSolver, with its twisted factors): the reference of the
 * target "FEM + BDF-2 and generalized-alpha within 2.5 banded solves per
 * step". Each solve starts from the same right-hand side (a solve applied
 * again to its own result would shrink it by about c^2 M per solve into
 * denormal numbers); the copy of that right-hand side is timed alone in the
 * same turns and taken off. The fastest of @p batches batches counts.
 */
inline double banded_solve_microseconds(const ProgramParameters& p,
                                        const unsigned int batches = 10,
                                        const unsigned int repetitions = 2000)
{
  using Clock = std::chrono::steady_clock;
  CaseRunner simulation(p.make_case(), {p.output.probe_positions, p.output.energy});
  const SemiDiscreteSystem& system = simulation.system();
  const double c = 1.5 / p.time_integration.time_step;
  dealii::SparseMatrix<double> S;
  assemble_iteration_matrix(system, c, c * c, S);
  SparseDirectSolver solver;
  solver.factorize(S, "S");
  const unsigned int n = system.n_dofs();
  dealii::Vector<double> b(n), x(n);
  for (unsigned int i = 0; i < n; ++i)
    b[i] = 1. + 1e-3 * (i % 7);
  const auto per_repetition = [&](const auto& work)
  {
    const auto t0 = Clock::now();
    for (unsigned int k = 0; k < repetitions; ++k)
      work();
    return 1e6 * std::chrono::duration<double>(Clock::now() - t0).count() / repetitions;
  };
  double copy_and_solve = 1e300, copy = 1e300;
  for (unsigned int batch = 0; batch < batches; ++batch)
  {
    copy_and_solve = std::min(copy_and_solve, per_repetition(
                                                  [&]
                                                  {
                                                    x = b;
                                                    solver.solve(x);
                                                  }));
    copy = std::min(copy, per_repetition(
                              [&]
                              {
                                x = b;
                                asm volatile("" : : "r"(x.begin()) : "memory");
                              }));
  }
  return copy_and_solve - copy;
}
} // namespace pantocat::bench
