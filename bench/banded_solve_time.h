#pragma once

#include <pantocat/app/program_parameters.h>
#include <pantocat/lac/sparse_direct_solver.h>
#include <pantocat/simulation/case_runner.h>
#include <pantocat/system/sparse_row.h>
#include <pantocat/time/fixed_constraint_schur.h>
#include <pantocat/time/iteration_matrix.h>

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

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
/**
 * Microseconds of one solve of the *constrained* system of the case @p p,
 *
 *   [S  G_F^T] [x     ]   [b]
 *   [G_F   0 ] [lambda] = [0],
 *
 * with S the BDF-2 iteration matrix as in banded_solve_microseconds() and
 * G_F the rows of its rigid fixed constraints (droppers, supports), by the
 * fastest way this library has (the way the implicit steps solve): x0 =
 * S^-1 b (one banded solve), lambda = (G_F S^-1 G_F^T)^-1 G_F x0 (the Schur
 * complement's banded factor, FixedConstraintSchur, computed and factorised
 * before the timing, as an integrator does once per active set), x = x0 -
 * S^-1 G_F^T lambda (its truncated columns). Without fixed constraints it is
 * banded_solve_microseconds(). The solution is checked (|G_F x| at
 * round-off of |G_F| |x|) before it is timed; the copy of b is taken off as
 * there. The reference of the target read as "one banded solve of the same
 * (constrained) system".
 */
inline double constrained_solve_microseconds(const ProgramParameters& p,
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

  std::vector<SparseRow> rows;
  ConstraintState state;
  for (const auto& constraint : system.constraints)
    if (!constraint->depends_on_time() && !constraint->is_compliant())
    {
      constraint->evaluate(0., state, 0);
      rows.push_back(state.G);
    }
  const unsigned int m = rows.size();
  std::vector<const SparseRow*> row_pointers;
  CompressedRows G;
  for (const SparseRow& row : rows)
  {
    row_pointers.push_back(&row);
    G.push_back(row);
  }
  FixedConstraintSchur schur;
  if (m > 0)
  {
    schur.initialize(row_pointers, solver, n, "G_F S^-1 G_F^T");
    schur.select(std::vector<bool>(m, true));
  }

  dealii::Vector<double> b(n), x(n), lambda(m);
  std::vector<double> factors(m);
  for (unsigned int i = 0; i < n; ++i)
    b[i] = 1. + 1e-3 * (i % 7);
  const auto solve = [&]
  {
    x = b;
    solver.solve(x);
    if (m == 0)
      return;
    for (unsigned int k = 0; k < m; ++k)
      lambda[k] = G.dot(k, x.begin());
    schur.solve(lambda);
    for (unsigned int k = 0; k < m; ++k)
      factors[k] = -lambda[k];
    schur.add_columns(factors, x);
  };

  solve();
  for (unsigned int k = 0; k < m; ++k)
  {
    double scale = 0.;
    for (unsigned int e = 0; e < rows[k].size(); ++e)
      scale += std::abs(rows[k].value[e] * x[rows[k].index[e]]);
    if (!(std::abs(G.dot(k, x.begin())) <= 1e-10 * scale))
      throw std::runtime_error("constrained solve: |G_F x| = " +
                               std::to_string(std::abs(G.dot(k, x.begin()))) +
                               " for constraint " + std::to_string(k) +
                               ", not at round-off of " + std::to_string(scale));
  }

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
    copy_and_solve = std::min(copy_and_solve, per_repetition(solve));
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
