// Time per step of the integrators on the paper's benchmark (32 m/s), for
// N+1 = 500, 2000, 8000, against simple baselines measured in the same run:
//  - FDM + half-explicit against a minimal hand-written loop on plain arrays
//    that does the same arithmetic (stencils, diagonal masses, the contact
//    row, the 3x3 and 6x6 multiplier systems);
//  - FEM + BDF-2 against one hand-written banded Cholesky solve of the same size;
// then the sparse direct solvers (banded Cholesky, UMFPACK, Trilinos KLU) on the
// same BDF-2 iteration matrices.
// Every figure is the fastest of 5 batches (noisy machines).
// Usage: bench_integrators [steps] [N+1 ...]; prints a table (Markdown).
#include <pantocat/app/program_parameters.h>
#include <pantocat/lac/sparse_direct_solver.h>
#include <pantocat/pantograph/pantograph_parameters.h>
#include <pantocat/simulation/case_runner.h>
#include <pantocat/space/smoothed_delta.h>
#include <pantocat/time/time_integrator.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <vector>

using namespace pantocat;
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

/// Gaussian elimination with partial pivoting, in place (baseline only).
void solve_dense(int n, double* A, double* b)
{
  for (int k = 0; k < n; ++k)
  {
    int p = k;
    for (int i = k + 1; i < n; ++i)
      if (std::abs(A[i * n + k]) > std::abs(A[p * n + k]))
        p = i;
    for (int j = 0; j < n; ++j)
      std::swap(A[k * n + j], A[p * n + j]);
    std::swap(b[k], b[p]);
    for (int i = k + 1; i < n; ++i)
    {
      const double f = A[i * n + k] / A[k * n + k];
      for (int j = k; j < n; ++j)
        A[i * n + j] -= f * A[k * n + j];
      b[i] -= f * b[k];
    }
  }
  for (int i = n - 1; i >= 0; --i)
  {
    for (int j = i + 1; j < n; ++j)
      b[i] -= A[i * n + j] * b[j];
    b[i] /= A[i * n + i];
  }
}

/**
 * The FDM + half-explicit step (39)-(41) written out on plain arrays for the
 * benchmark's structure: carrier (tridiagonal), contact wire (pentadiagonal),
 * two-mass pantograph, two droppers, the smoothed contact. Microseconds per step.
 */
double baseline_fdm_half_explicit(unsigned int n_intervals, double dt, unsigned int steps)
{
  const CatenaryParameters c;
  const TwoMassPantographParameters pp;
  const int N = n_intervals - 1; // unknowns per wire
  const double dx = c.span / n_intervals;
  const double tc = c.carrier.tension / dx, tw = c.contact_wire.tension / dx,
               bw = c.contact_wire.bending_stiffness / (dx * dx * dx);
  const double mc = c.carrier.mass_per_length * dx,
               mw = c.contact_wire.mass_per_length * dx;
  const double dc = c.carrier.damping * dx, dw = c.contact_wire.damping * dx;
  const int n = 2 * N + 2, P = 2 * N;
  std::vector<double> q(n, 0.), v(n, 0.), vp(n, 0.), a(n), f(n), w(n);
  for (int i = 0; i < N; ++i)
    f[i] = -c.carrier.mass_per_length * c.gravity * dx,
    f[N + i] = -c.contact_wire.mass_per_length * c.gravity * dx;
  f[P + 1] = pp.uplift_force;
  // A physically meaningless but generic state (the timing does not depend on it).
  for (int i = 0; i < n; ++i)
    q[i] = 1e-3 * std::sin(0.1 * i);
  const int d1 = static_cast<int>(std::floor(5.5 / dx + 0.5)) - 1,
            d2 = static_cast<int>(std::floor(14.5 / dx + 0.5)) - 1;
  const double z = 0.95 - c.support_height;
  const SmoothedDelta delta(0.2);
  // Contact rows at a time: wire indices first..last, G and G_t values.
  struct Row
  {
    int first = 0, last = 0;
    std::vector<double> G, Gt, Gtt;
  };
  const std::size_t support = 2 * static_cast<std::size_t>(std::ceil(0.2 / dx)) + 4;
  auto contact_row = [&](double t, Row& r, bool second)
  {
    const double x = 2. + 32. * t, xd = 32.;
    r.first = std::max(1, static_cast<int>(std::floor((x - 0.2) / dx + 0.5)));
    r.last = std::min(N, static_cast<int>(std::floor((x + 0.2) / dx + 0.5)));
    for (int i = r.first; i <= r.last; ++i)
    {
      const double lo = (i - 0.5) * dx - x, hi = (i + 0.5) * dx - x;
      r.G[i - r.first] = delta.integral_up_to(hi) - delta.integral_up_to(lo);
      r.Gt[i - r.first] = -xd * (delta.value(hi) - delta.value(lo));
      if (second)
        r.Gtt[i - r.first] =
            xd * xd * (delta.derivative(hi, 1) - delta.derivative(lo, 1));
    }
  };
  auto dot =
      [&](const Row& r, const std::vector<double>& row, const std::vector<double>& x)
  {
    double s = 0.;
    for (int i = r.first; i <= r.last; ++i)
      s += row[i - r.first] * x[N + i - 1];
    return s;
  };
  const double m1 = pp.head_mass, m2 = pp.frame_mass, c1 = pp.head_stiffness,
               e1 = pp.head_damping, e2 = pp.frame_damping;
  Row rn, rh, r1;
  for (Row* r : {&rn, &rh, &r1})
    r->G.resize(support), r->Gt.resize(support), r->Gtt.resize(support);
  double t = 0.;
  const auto t0 = Clock::now();
  for (unsigned int step = 0; step < steps; ++step)
  {
    contact_row(t, rn, true);
    contact_row(t + 0.5 * dt, rh, false);
    contact_row(t + dt, r1, false);
    // Step 1: forces with the smoothed damping (41), diagonal masses.
    for (int i = 0; i < n; ++i)
      w[i] = 0.5 * (vp[i] + v[i]);
    for (int i = 0; i < N; ++i)
    {
      const double l = i > 0 ? q[i - 1] : 0., r = i + 1 < N ? q[i + 1] : 0.;
      a[i] = (f[i] - tc * (2. * q[i] - l - r) - dc * w[i]) / (mc + 0.5 * dt * dc);
    }
    for (int i = 0; i < N; ++i)
    {
      const double* u = &q[N];
      const double l1 = i > 0 ? u[i - 1] : 0., r1v = i + 1 < N ? u[i + 1] : 0.,
                   l2 = i > 1 ? u[i - 2] : 0., r2 = i + 2 < N ? u[i + 2] : 0.;
      const double diag = (i == 0 || i == N - 1) ? 5. : 6.;
      a[N + i] = (f[N + i] - tw * (2. * u[i] - l1 - r1v) -
                  bw * (diag * u[i] - 4. * (l1 + r1v) + l2 + r2) - dw * w[N + i]) /
                 (mw + 0.5 * dt * dw);
    }
    {
      const double s = q[P] - q[P + 1], sd = w[P] - w[P + 1];
      const double F1 = -c1 * s - e1 * sd,
                   F2 = c1 * s + e1 * sd - e2 * w[P + 1] + f[P + 1];
      // 2x2 smoothed mass of the pantograph: [m1 + h/2 e1, -h/2 e1; -h/2 e1, m2 + h/2
      // (e1+e2)]
      const double A11 = m1 + 0.5 * dt * e1, A12 = -0.5 * dt * e1,
                   A22 = m2 + 0.5 * dt * (e1 + e2), det = A11 * A22 - A12 * A12;
      a[P] = (A22 * F1 - A12 * F2) / det;
      a[P + 1] = (A11 * F2 - A12 * F1) / det;
    }
    // Multipliers lambda (3x3): rows d1, d2, contact; columns M~^-1 G^T.
    double S[9], b[3];
    const double ic = 1. / (mc + 0.5 * dt * dc), iw = 1. / (mw + 0.5 * dt * dw);
    const double head_inv =
        (m2 + 0.5 * dt * (e1 + e2)) /
        ((m1 + 0.5 * dt * e1) * (m2 + 0.5 * dt * (e1 + e2)) - 0.25 * dt * dt * e1 * e1);
    double gg = 0.;
    for (int i = rn.first; i <= rn.last; ++i)
      gg += rn.G[i - rn.first] * rn.G[i - rn.first] * iw;
    const double gd1 =
        (d1 + 1 >= rn.first && d1 + 1 <= rn.last) ? rn.G[d1 + 1 - rn.first] * iw : 0.;
    const double gd2 =
        (d2 + 1 >= rn.first && d2 + 1 <= rn.last) ? rn.G[d2 + 1 - rn.first] * iw : 0.;
    S[0] = iw + ic, S[1] = 0., S[2] = gd1;
    S[3] = 0., S[4] = iw + ic, S[5] = gd2;
    S[6] = gd1, S[7] = gd2, S[8] = gg + head_inv;
    b[0] = -(a[N + d1] - a[d1]);
    b[1] = -(a[N + d2] - a[d2]);
    b[2] = -(dot(rn, rn.G, a) - a[P] + 2. * dot(rn, rn.Gt, v) + dot(rn, rn.Gtt, q));
    solve_dense(3, S, b);
    a[N + d1] += b[0] * iw, a[d1] -= b[0] * ic;
    a[N + d2] += b[1] * iw, a[d2] -= b[1] * ic;
    for (int i = rn.first; i <= rn.last; ++i)
      a[N + i - 1] += b[2] * rn.G[i - rn.first] * iw;
    a[P] -= b[2] * head_inv;
    // Step 2: leapfrog, then the 6x6 projection (eta, mu) at t_{n+1}.
    for (int i = 0; i < n; ++i)
    {
      const double vn = vp[i] + 2. * dt * a[i];
      w[i] = q[i] + 0.5 * dt * (v[i] + vn);
      vp[i] = v[i];
      v[i] = vn;
    }
    double T[36] = {0.}, e[6];
    const double jm = 1. / mw, jc = 1. / c.carrier.mass_per_length / dx;
    T[0] = dt * (jm + jc), T[7] = dt * (jm + jc), T[14] = dt * (jm + 1. / m1);
    T[21] = 2. * dt * (jm + jc), T[28] = 2. * dt * (jm + jc),
    T[35] = 2. * dt * (jm + 1. / m1);
    e[0] = -(w[N + d1] - w[d1] + z), e[1] = -(w[N + d2] - w[d2] + z);
    e[2] = -(dot(r1, r1.G, w) - w[P]);
    e[3] = -(v[N + d1] - v[d1]), e[4] = -(v[N + d2] - v[d2]);
    e[5] = -(dot(r1, r1.Gt, w) + dot(r1, r1.G, v) - v[P]);
    solve_dense(6, T, e);
    for (int k = 0; k < 2; ++k)
    {
      const int d = k == 0 ? d1 : d2;
      w[N + d] += dt * e[k] * jm, w[d] -= dt * e[k] * jc;
      v[N + d] += 2. * dt * e[3 + k] * jm, v[d] -= 2. * dt * e[3 + k] * jc;
    }
    for (int i = rh.first; i <= rh.last; ++i)
      w[N + i - 1] += dt * (e[2] * rh.G[i - rh.first] + e[5] * rh.Gt[i - rh.first]) * jm;
    w[P] -= dt * e[2] / m1;
    v[P] -= 2. * dt * e[5] / m1;
    std::swap(q, w);
    t += dt;
  }
  return 1e6 * seconds_since(t0) / steps;
}

/// One hand-written banded Cholesky solve (forward and backward substitution
/// with precomputed reciprocal pivots) with half bandwidth 3 (the Hermite
/// wire's) and size n: microseconds per solve.
double baseline_banded_solve(int n, unsigned int repetitions)
{
  const int kd = 3;
  std::vector<double> L((kd + 1) * n), x(n, 1.);
  for (int i = 0; i < n; ++i) // SPD band: diagonally dominant
    for (int k = 0; k <= kd; ++k)
      L[i * (kd + 1) + k] = k == 0 ? 10. : -1. / (1. + k);
  // Cholesky in place: row i holds L(i, i-k) at k.
  for (int i = 0; i < n; ++i)
  {
    for (int k = kd; k >= 1; --k)
    {
      const int j = i - k;
      if (j < 0)
        continue;
      double s = L[i * (kd + 1) + k];
      for (int m = k + 1; m <= kd && j - (m - k) >= 0; ++m)
        s -= L[i * (kd + 1) + m] * L[j * (kd + 1) + (m - k)];
      L[i * (kd + 1) + k] = s / L[j * (kd + 1)];
    }
    double s = L[i * (kd + 1)];
    for (int k = 1; k <= kd && i - k >= 0; ++k)
      s -= L[i * (kd + 1) + k] * L[i * (kd + 1) + k];
    L[i * (kd + 1)] = std::sqrt(s);
  }
  std::vector<double> reciprocal(n);
  for (int i = 0; i < n; ++i)
    reciprocal[i] = 1. / L[i * (kd + 1)];
  const auto t0 = Clock::now();
  for (unsigned int r = 0; r < repetitions; ++r)
  {
    for (int i = 0; i < n; ++i) // fresh right-hand side: no denormals
      x[i] = 1. + 1e-3 * (i % 7);
    for (int i = 0; i < n; ++i)
    {
      double s = x[i];
      for (int k = 1; k <= kd && i - k >= 0; ++k)
        s -= L[i * (kd + 1) + k] * x[i - k];
      x[i] = s * reciprocal[i];
    }
    for (int i = n - 1; i >= 0; --i)
    {
      double s = x[i];
      for (int k = 1; k <= kd && i + k < n; ++k)
        s -= L[(i + k) * (kd + 1) + k] * x[i + k];
      x[i] = s * reciprocal[i];
    }
  }
  volatile double sink = x[n / 2];
  (void)sink;
  return 1e6 * seconds_since(t0) / repetitions;
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

int main(int argc, char** argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  dealii::MultithreadInfo::set_thread_limit(1); // as pantocat-fem does
  const unsigned int steps = argc > 1 ? std::atoi(argv[1]) : 2000;
  std::vector<unsigned int> grids;
  for (int i = 2; i < argc; ++i)
    grids.push_back(std::atoi(argv[i]));
  if (grids.empty())
    grids = {500, 2000, 8000};

  std::cout
      << "| N+1 | FDM+HE [us/step] | hand-written loop [us/step] | ratio | FEM+BDF2 "
         "[us/step] | banded solve [us] | ratio | FDM+BDF2 [us/step] |\n"
      << "|---|---|---|---|---|---|---|---|\n";
  for (const unsigned int n : grids)
  {
    // dt = c dx^2 as in Sec. 5.2, scaled from the paper's 5e-5 s at N+1 = 500.
    const double scale = 500. / n, dt = 5e-5 * scale * scale;
    const double he =
        library_step(benchmark(n, SpaceMethod::fdm, "half-explicit", dt), steps);
    double loop = 1e300;
    for (unsigned int b = 0; b < batches; ++b)
      loop = std::min(loop,
                      baseline_fdm_half_explicit(n, dt, std::max(1u, steps / batches)));
    const unsigned int bdf_steps = std::max(20u, steps / (n / 250));
    const double bdf =
        library_step(benchmark(n, SpaceMethod::fem, "bdf2", dt), bdf_steps);
    const double banded =
        baseline_banded_solve(3 * n + 1, 500); // FEM system size: N + (2N+2) + 2
    const double fdm_bdf =
        library_step(benchmark(n, SpaceMethod::fdm, "bdf2", dt), bdf_steps);
    std::cout << std::setprecision(3) << "| " << n << " | " << he << " | " << loop
              << " | " << he / loop << " | " << bdf << " | " << banded << " | "
              << bdf / banded << " | " << fdm_bdf << " |" << std::endl;
  }
  compare_linear_solvers(grids, steps / 4);
}
