#include <pantocat/base/input_error.h>
#include <pantocat/time/bdf2_integrator.h>

#include <cmath>
#include <sstream>

namespace pantocat
{
void Bdf2Integrator::Triple::reinit(const unsigned int n)
{
  q.reinit(n);
  v.reinit(n);
  a.reinit(n);
}

void Bdf2Integrator::Triple::add(const double factor, const Triple& other)
{
  q.add(factor, other.q);
  v.add(factor, other.v);
  a.add(factor, other.a);
}

/// The block solver for one c: S = K + c D + c^2 M and the constraint columns.
struct Bdf2Integrator::Stage
{
  Stage(const SemiDiscreteSystem& system, const MassInverse& mass_inverse, double c)
      : system(system), mass_inverse(mass_inverse), c(c)
  {
    dealii::SparseMatrix<double> S(*system.sparsity);
    S.copy_from(system.stiffness);
    S.add(c, system.damping);
    S.add(c * c, system.mass);
    S_inverse.factorize(S, "BDF iteration matrix K + c D + c^2 M");
    const unsigned int n = system.n_dofs(), m = system.n_constraints();
    for (auto* columns : {&X_lambda, &X_eta, &X_mu})
    {
      columns->resize(m);
      for (auto& x : *columns)
        x.reinit(n);
    }
    base.reinit(n);
    u1.reinit(n);
    u2.reinit(n);
    rhs.reinit(n);
  }

  /// Solves the (q, v, a) block for right-hand sides (b1, b2, b3), given
  /// u1 = M^-1 b1 and u2 = M^-1 b2:
  ///   (K + c D + c^2 M) q = b3 + b2 + D u1 + c b1,  v = c q - u1,  a = c v - u2.
  void solve(const dealii::Vector<double>& b1, const dealii::Vector<double>& b2,
             const dealii::Vector<double>& b3, Triple& x)
  {
    system.damping.vmult(rhs, u1);
    rhs += b3;
    rhs += b2;
    rhs.add(c, b1);
    S_inverse.solve(rhs);
    x.q = rhs;
    x.v.equ(c, x.q);
    x.v -= u1;
    x.a.equ(c, x.v);
    x.a -= u2;
  }

  /// Columns of constraint i with rows @p s (at the new time).
  void columns(unsigned int i, const ConstraintState& s)
  {
    const unsigned int n = system.n_dofs();
    dealii::Vector<double> G(n), Gt(n), zero(n);
    s.G.add_transpose_to(G, 1.);
    s.G_t.add_transpose_to(Gt, 1.);
    // lambda: b = (0, 0, G^T).
    u1 = 0.;
    u2 = 0.;
    solve(zero, zero, G, X_lambda[i]);
    // mu: b = (G^T, 0, 0).
    u1 = G;
    mass_inverse.apply(u1);
    dealii::Vector<double> MinvG = u1;
    solve(G, zero, zero, X_mu[i]);
    // eta: b = (G_t^T, G^T, 0).
    u1 = Gt;
    mass_inverse.apply(u1);
    u2 = MinvG;
    solve(Gt, G, zero, X_eta[i]);
  }

  const SemiDiscreteSystem& system;
  const MassInverse& mass_inverse;
  double c;
  SparseDirectSolver S_inverse;
  std::vector<Triple> X_lambda, X_eta, X_mu;
  std::vector<bool> constant_columns_done;
  Triple base;
  dealii::Vector<double> u1, u2, rhs;
};

Bdf2Integrator::Bdf2Integrator(const SemiDiscreteSystem& system, const double time_step,
                               const unsigned int max_iterations)
    : TimeIntegrator(system), dt(time_step), at_next(system),
      active_set(system, max_iterations)
{
  mass_inverse.initialize(system.mass, system.mass_is_diagonal, "mass matrix M");
}

Bdf2Integrator::~Bdf2Integrator() = default;

DynamicState Bdf2Integrator::implicit_step(Stage& s, const dealii::Vector<double>& rho_q,
                                           const dealii::Vector<double>& rho_v,
                                           const double t1,
                                           const std::vector<bool>& active_at_start)
{
  const unsigned int n = system.n_dofs(), m_all = system.n_constraints();
  const auto& rows = at_next.at(t1);
  // Base solution: b = (M rho_q, M rho_v, f), so M^-1 b1 = rho_q, M^-1 b2 = rho_v.
  dealii::Vector<double> b1(n), b2(n);
  system.mass.vmult(b1, rho_q);
  system.mass.vmult(b2, rho_v);
  s.u1 = rho_q;
  s.u2 = rho_v;
  s.solve(b1, b2, system.load, s.base);
  // Constraint columns: constant rows once per stage, moving rows every step.
  if (s.constant_columns_done.empty())
  {
    s.constant_columns_done.assign(m_all, false);
    for (unsigned int i = 0; i < m_all; ++i)
      if (!system.constraints[i]->depends_on_time())
      {
        s.columns(i, rows[i]);
        s.constant_columns_done[i] = true;
      }
  }
  for (unsigned int i = 0; i < m_all; ++i)
    if (system.constraints[i]->depends_on_time())
      s.columns(i, rows[i]);

  DynamicState x;
  x.t = t1;
  x.lambda.assign(m_all, 0.);
  std::vector<double> gaps(m_all);
  Triple sol;
  sol.reinit(n);
  active_set.start(active_at_start);
  for (;;)
  {
    const auto& A = active_set.active_indices();
    const unsigned int m = A.size();
    small.reinit(3 * m, 3 * m);
    small_rhs.reinit(3 * m);
    small_solution.reinit(3 * m);
    // Rows: g, dg/dt, d2g/dt2 of each active constraint; columns: lambda, eta, mu.
    auto functionals = [&](const ConstraintState& r, const Triple& y, double out[3])
    {
      out[0] = r.G.dot(y.q);
      out[1] = r.G_t.dot(y.q) + r.G.dot(y.v);
      out[2] = r.G_tt.dot(y.q) + 2. * r.G_t.dot(y.v) + r.G.dot(y.a);
    };
    double f[3];
    for (unsigned int k = 0; k < m; ++k)
    {
      const ConstraintState& r = rows[A[k]];
      for (unsigned int l = 0; l < m; ++l)
      {
        const Triple* columns[3] = {&s.X_lambda[A[l]], &s.X_eta[A[l]], &s.X_mu[A[l]]};
        for (unsigned int c = 0; c < 3; ++c)
        {
          functionals(r, *columns[c], f);
          for (unsigned int row = 0; row < 3; ++row)
            small(row * m + k, c * m + l) = f[row];
        }
      }
      functionals(r, s.base, f);
      small_rhs(k) = -(f[0] + r.z);
      small_rhs(m + k) = -(f[1] + r.z_t);
      small_rhs(2 * m + k) = -(f[2] + r.z_tt);
    }
    if (m > 0)
    {
      small.gauss_jordan();
      small.vmult(small_solution, small_rhs);
      for (const double value : small_solution)
        if (!std::isfinite(value))
        {
          std::ostringstream msg;
          msg << "the active constraints are linearly dependent at t = " << t1 << " s";
          throw SimulationError(msg.str());
        }
    }
    sol.q = s.base.q;
    sol.v = s.base.v;
    sol.a = s.base.a;
    std::fill(x.lambda.begin(), x.lambda.end(), 0.);
    for (unsigned int l = 0; l < m; ++l)
    {
      sol.add(small_solution(l), s.X_lambda[A[l]]);
      sol.add(small_solution(m + l), s.X_eta[A[l]]);
      sol.add(small_solution(2 * m + l), s.X_mu[A[l]]);
      x.lambda[A[l]] = small_solution(l);
    }
    for (unsigned int i = 0; i < m_all; ++i)
      gaps[i] = rows[i].position_residual(sol.q);
    if (active_set.accept(gaps, x.lambda, t1, step_number + 1))
      break;
    ++stats.active_set_iterations;
  }
  stats.active_set_changes += active_set.changes_in_step();
  x.q.swap(sol.q);
  x.v.swap(sol.v);
  x.a.swap(sol.a);
  x.active = active_set.active();
  return x;
}

void Bdf2Integrator::initialize(const DynamicState& initial)
{
  current = initial;
  previous = DynamicState();
  step_number = 0;
}

void Bdf2Integrator::richardson_start()
{
  // Backward Euler with dt, and twice with dt/2; extrapolate (2nd order), Sec. 5.2.
  const DynamicState x0 = current;
  Stage full(system, mass_inverse, 1. / dt), half(system, mass_inverse, 2. / dt);
  dealii::Vector<double> rho_q(x0.q), rho_v(x0.v);
  rho_q *= 1. / dt;
  rho_v *= 1. / dt;
  const DynamicState coarse = implicit_step(full, rho_q, rho_v, x0.t + dt, x0.active);
  rho_q = x0.q;
  rho_v = x0.v;
  rho_q *= 2. / dt;
  rho_v *= 2. / dt;
  const DynamicState mid = implicit_step(half, rho_q, rho_v, x0.t + 0.5 * dt, x0.active);
  rho_q = mid.q;
  rho_v = mid.v;
  rho_q *= 2. / dt;
  rho_v *= 2. / dt;
  DynamicState fine = implicit_step(half, rho_q, rho_v, x0.t + dt, mid.active);
  if (fine.active == coarse.active)
  {
    fine.q.sadd(2., -1., coarse.q);
    fine.v.sadd(2., -1., coarse.v);
    fine.a.sadd(2., -1., coarse.a);
    for (unsigned int i = 0; i < fine.lambda.size(); ++i)
      fine.lambda[i] = 2. * fine.lambda[i] - coarse.lambda[i];
  }
  // else: the active set changed inside the first step; keep the dt/2 result.
  previous = x0;
  current = std::move(fine);
}

void Bdf2Integrator::advance()
{
  if (step_number == 0)
    richardson_start();
  else
  {
    if (!bdf2)
      bdf2 = std::make_unique<Stage>(system, mass_inverse, 1.5 / dt);
    // rho = (4 x_n - x_{n-1}) / (2 dt)
    dealii::Vector<double> rho_q(current.q), rho_v(current.v);
    rho_q.sadd(2. / dt, -0.5 / dt, previous.q);
    rho_v.sadd(2. / dt, -0.5 / dt, previous.v);
    DynamicState next =
        implicit_step(*bdf2, rho_q, rho_v, current.t + dt, current.active);
    previous = std::move(current);
    current = std::move(next);
  }
  ++step_number;
  ++stats.steps;
}
} // namespace pantocat
