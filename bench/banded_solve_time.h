#pragma once

#include <pantocat/app/program_parameters.h>
#include <pantocat/lac/sparse_direct_solver.h>
#include <pantocat/simulation/case_runner.h>
#include <pantocat/system/pattern_operators.h>
#include <pantocat/lac/sparse_row.h>
#include <pantocat/constrained_fast/fixed_constraint_schur.h>
#include <pantocat/constrained_fast/iteration_matrix.h>
#include <pantocat/constrained_fast/mass_inverse.h>

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
/// The rows G_k of the rigid constraints with constant rows (droppers, supports).
inline std::vector<SparseRow> rigid_fixed_rows(const SemiDiscreteSystem& system)
{
  std::vector<SparseRow> rows;
  ConstraintState state;
  for (const auto& constraint : system.constraints)
    if (!constraint->depends_on_time() && !constraint->is_compliant())
    {
      constraint->evaluate(0., state, 0);
      rows.push_back(state.G);
    }
  return rows;
}

/// The fastest of @p batches batches of @p repetitions calls of @p work, in
/// microseconds per call, less the same for @p overhead (timed in turns).
template <typename Work, typename Overhead>
double microseconds_per_call(const Work& work, const Overhead& overhead,
                             const unsigned int batches, const unsigned int repetitions)
{
  using Clock = std::chrono::steady_clock;
  const auto per_repetition = [&](const auto& f)
  {
    const auto t0 = Clock::now();
    for (unsigned int k = 0; k < repetitions; ++k)
      f();
    return 1e6 * std::chrono::duration<double>(Clock::now() - t0).count() / repetitions;
  };
  double with = 1e300, without = 1e300;
  for (unsigned int batch = 0; batch < batches; ++batch)
  {
    with = std::min(with, per_repetition(work));
    without = std::min(without, per_repetition(overhead));
  }
  return with - without;
}

/// microseconds_per_call() of @p work, which starts with x = b, less the copy.
template <typename Work>
double microseconds_less_the_copy(const Work& work, dealii::Vector<double>& x,
                                  const dealii::Vector<double>& b,
                                  const unsigned int batches,
                                  const unsigned int repetitions)
{
  return microseconds_per_call(
      work,
      [&]
      {
        x = b;
        asm volatile("" : : "r"(x.begin()) : "memory");
      },
      batches, repetitions);
}

/// The case of the parameters @p p and its BDF-2 iteration matrix S = K + c D
/// + c^2 M (c = 1.5/dt), factorised by the library's banded Cholesky.
struct FactorisedCase
{
  explicit FactorisedCase(const ProgramParameters& p)
      : simulation(p.make_case(), {p.output.probe_positions, p.output.energy}),
        c(1.5 / p.time_integration.time_step)
  {
    assemble_iteration_matrix(system(), c, c * c, S);
    solver.factorize(S, "S");
  }
  const SemiDiscreteSystem& system() const { return simulation.system(); }
  /// A right-hand side of order 1 that is not a multiple of a smooth mode.
  dealii::Vector<double> right_hand_side() const
  {
    dealii::Vector<double> b(system().n_dofs());
    for (unsigned int i = 0; i < b.size(); ++i)
      b[i] = 1. + 1e-3 * (i % 7);
    return b;
  }

  CaseRunner simulation;
  double c;
  dealii::SparseMatrix<double> S;
  SparseDirectSolver solver;
};

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
  const FactorisedCase fem(p);
  const dealii::Vector<double> b = fem.right_hand_side();
  dealii::Vector<double> x(b.size());
  return microseconds_less_the_copy(
      [&]
      {
        x = b;
        fem.solver.solve(x);
      },
      x, b, batches, repetitions);
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
  const FactorisedCase fem(p);
  const SparseDirectSolver& solver = fem.solver;
  const std::vector<SparseRow> rows = rigid_fixed_rows(fem.system());
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
    schur.initialize(row_pointers, solver, fem.system().n_dofs(), "G_F S^-1 G_F^T");
    schur.select(std::vector<bool>(m, true));
  }

  const dealii::Vector<double> b = fem.right_hand_side();
  dealii::Vector<double> x(b.size()), lambda(m);
  std::vector<double> factors(m);
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

  return microseconds_less_the_copy(solve, x, b, batches, repetitions);
}

/**
 * Microseconds of a lower bound of one FEM BDF-2 step of the case @p p with
 * its rigid fixed constraints (the droppers), from the library's own kernels
 * at their rates and a minimal update, without the contact, the multiplier
 * systems and the active set:
 *  1. the right-hand side f + M h' + E r and the solve with S
 *     (PatternOperators::solve_history(), as the step forms them);
 *  2. the position-level correction x += S^-1 G_F^T lambda, one output
 *     (FixedConstraintSchur::add_columns(): the stored columns, or one
 *     solve where they would read more, as on a 100 m span at m = 200);
 *  3. one pass that a BDF-2 step cannot do without: reads x (which is
 *     q_(n+1), as the step keeps it in the solve's vector), q_n, q_(n-1),
 *     v_n, v_(n-1), writes v_(n+1) and the next history h' (seven streams;
 *     the step's own pass streams eleven);
 *  4. the velocity-level correction v += M^-1 G_F^T eta (one output).
 * Without fixed constraints, 1 and 3. The step as built does more than this
 * in every part (two outputs per correction, the contact's columns, the
 * multipliers), so its time is at least this one's.
 */
inline double bdf2_step_floor_microseconds(const ProgramParameters& p,
                                           const unsigned int batches = 10,
                                           const unsigned int repetitions = 1000)
{
  const FactorisedCase fem(p);
  const SemiDiscreteSystem& system = fem.system();
  const SparseDirectSolver& solver = fem.solver;
  const double dt = p.time_integration.time_step, c = fem.c;
  const PatternOperators operators(system, {c * c, c, 1.});
  const unsigned int n = system.n_dofs();

  const std::vector<SparseRow> rows = rigid_fixed_rows(system);
  const unsigned int m = rows.size();
  std::vector<const SparseRow*> row_pointers;
  for (const SparseRow& row : rows)
    row_pointers.push_back(&row);
  FixedConstraintSchur at_S, at_M;
  MassInverse mass;
  if (m > 0)
  {
    mass.initialize(system.mass, system.mass_is_diagonal, "M");
    at_S.initialize(row_pointers, solver, n, "G_F S^-1 G_F^T");
    at_M.initialize(row_pointers, mass, n, "G_F M^-1 G_F^T");
  }
  std::vector<double> lambda(m), eta(m);
  for (unsigned int k = 0; k < m; ++k)
  {
    lambda[k] = 1e-6 * (1. + 1e-3 * (k % 5)); // small: x stays near the solve's
    eta[k] = -lambda[k];
  }

  dealii::Vector<double> h(n), r(n), x(n), v(n), q_n(n), q_nm1(n), v_n(n), v_nm1(n);
  for (unsigned int i = 0; i < n; ++i)
  {
    q_n[i] = 1e-3 * (1. + 1e-3 * (i % 7));
    q_nm1[i] = 0.9 * q_n[i];
    v_n[i] = 1e-2 * (1. + 1e-3 * (i % 5));
    v_nm1[i] = 0.9 * v_n[i];
    h[i] = c * c * q_n[i];
  }
  // The BDF-2 relations v = c q - rho_q, h' = rho_v + c rho_q with
  // rho = (2 x_n - x_(n-1) / 2) / dt (the split's mu aside).
  const double fn = 2. / dt, fm = -0.5 / dt;
  const auto update = [&]
  {
    const double *__restrict xs = x.begin(), *__restrict qa = q_n.begin(),
                             *__restrict qb = q_nm1.begin(), *__restrict va = v_n.begin(),
                             *__restrict vb = v_nm1.begin();
    double* __restrict vo = v.begin(), * __restrict ho = h.begin();
    for (unsigned int i = 0; i < n; ++i)
    {
      const double rho_q = fn * qa[i] + fm * qb[i], rho_v = fn * va[i] + fm * vb[i];
      vo[i] = c * xs[i] - rho_q;
      ho[i] = rho_v + c * rho_q;
    }
  };
  const auto step = [&]
  {
    operators.solve_history(h, r, solver, x);
    if (m > 0)
      at_S.add_columns(lambda, x);
    update();
    if (m > 0)
      at_M.add_columns(eta, v);
  };
  step();
  if (!std::isfinite(x.l2_norm()) || !std::isfinite(v.l2_norm()))
    throw std::runtime_error("BDF-2 step floor: not finite");
  return microseconds_per_call(
      step, [] {}, batches, repetitions);
}
} // namespace pantocat::bench
