#include <pantocat/base/input_error.h>
#include <pantocat/time/bdf2_integrator.h>
#include <pantocat/time/multiplier_system.h>

#include <algorithm>
#include <array>
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
  bool constant_columns_ready = false;
  Triple base;
  dealii::Vector<double> u1, u2, rhs;
};

Bdf2Integrator::Bdf2Integrator(const SemiDiscreteSystem& system, const double time_step,
                               const unsigned int max_iterations,
                               const bool cache_responses)
    : TimeIntegrator(system), dt(time_step), at_next(system),
      active_set(system, max_iterations), use_cache(cache_responses)
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
  if (!s.constant_columns_ready)
  {
    s.constant_columns_ready = true;
    for (unsigned int i = 0; i < m_all; ++i)
      if (!system.constraints[i]->depends_on_time())
      {
        s.columns(i, rows[i]);
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
    solve_multiplier_system(small, small_rhs, small_solution, t1, "BDF step");
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

unsigned int Bdf2Integrator::unknowns_touched(const double t1)
{
  std::vector<unsigned int> all;
  for (const auto& r : at_next.at(t1))
    for (const SparseRow* row : {&r.G, &r.G_t})
      all.insert(all.end(), row->index.begin(), row->index.end());
  std::sort(all.begin(), all.end());
  return std::unique(all.begin(), all.end()) - all.begin();
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
    // The cache pays off while the rows touch few unknowns: each costs two
    // vector updates of length n per step, against about six solves for the
    // columns (doc/benchmarks.md).
    const bool cache =
        use_cache && unknowns_touched(current.t + dt) <= max_cached_unknowns;
    DynamicState next =
        cache ? cached_step(rho_q, rho_v, current.t + dt, current.active)
              : implicit_step(*bdf2, rho_q, rho_v, current.t + dt, current.active);
    previous = std::move(current);
    current = std::move(next);
  }
  ++step_number;
  ++stats.steps;
}

namespace
{
/// a x + b y + c z for sparse rows (small: linear search merge).
SparseRow combine(const SparseRow& x, double a, const SparseRow& y, double b,
                  const SparseRow& z = SparseRow(), double c = 0.)
{
  SparseRow out;
  for (const auto& [row, factor] :
       {std::pair<const SparseRow*, double>{&x, a}, {&y, b}, {&z, c}})
    for (std::size_t k = 0; k < row->size(); ++k)
    {
      const unsigned int i = row->index[k];
      std::size_t m = 0;
      while (m < out.size() && out.index[m] != i)
        ++m;
      if (m == out.size())
        out.add(i, 0.);
      out.value[m] += factor * row->value[k];
    }
  return out;
}
} // namespace

DynamicState Bdf2Integrator::cached_step(const dealii::Vector<double>& rho_q,
                                         const dealii::Vector<double>& rho_v,
                                         const double t1,
                                         const std::vector<bool>& active_at_start)
{
  using Op = ConstraintResponseCache::Operator;
  Stage& s = *bdf2;
  const double c = s.c;
  const unsigned int n = system.n_dofs(), m_all = system.n_constraints();
  const auto& rows = at_next.at(t1);
  if (!responses)
    responses = std::make_unique<ConstraintResponseCache>(s.S_inverse, mass_inverse,
                                                          system.damping);
  std::vector<const SparseRow*> touched;
  for (const auto& r : rows)
    touched.insert(touched.end(), {&r.G, &r.G_t});
  responses->update(touched);

  // Base: q0 = S^-1 (f + M (rho_v + c rho_q) + D rho_q), v0 = c q0 - rho_q.
  dealii::Vector<double> rhs(system.load), tmp(rho_v), q0(n);
  tmp.add(c, rho_q);
  system.mass.vmult_add(rhs, tmp);
  system.damping.vmult_add(rhs, rho_q);
  q0 = rhs;
  s.S_inverse.solve(q0);

  // Per constraint: the rows of the functionals g, dg/dt, d2g/dt2 written on q
  // (Lq), on M^-1 B1 (L1) and on M^-1 B2 (L2); doc/dynamics.md.
  struct Functionals
  {
    SparseRow Lq[3], L1[3], L2[3];
    double base[3];
  };
  std::vector<Functionals> F(m_all);
  for (unsigned int i = 0; i < m_all; ++i)
  {
    const ConstraintState& r = rows[i];
    Functionals& f = F[i];
    f.Lq[0] = r.G;
    f.Lq[1] = combine(r.G_t, 1., r.G, c);
    f.Lq[2] = combine(r.G_tt, 1., r.G_t, 2. * c, r.G, c * c);
    f.L1[1] = r.G;
    f.L1[2] = combine(r.G_t, 2., r.G, c);
    f.L2[2] = r.G;
    f.base[0] = f.Lq[0].dot(q0) + r.z;
    f.base[1] = f.Lq[1].dot(q0) - f.L1[1].dot(rho_q) + r.z_t;
    f.base[2] = f.Lq[2].dot(q0) - f.L1[2].dot(rho_q) - r.G.dot(rho_v) + r.z_tt;
  }
  // Contributions of lambda_l, eta_l, mu_l: terms (operator, row, factor) on
  // q, on M^-1 B1 and on M^-1 B2.
  struct Term
  {
    Op op;
    const SparseRow* row;
    double factor;
  };
  struct Contribution
  {
    std::vector<Term> q, b1, b2;
  };
  auto contribution = [&](unsigned int l, unsigned int kind)
  {
    const ConstraintState& r = rows[l];
    if (kind == 0) // lambda: S^-1 G^T
      return Contribution{{{Op::S, &r.G, 1.}}, {}, {}};
    if (kind == 1) // eta: S^-1 (G^T + c G_t^T) + S^-1 D M^-1 G_t^T; B1 = G_t^T, B2 = G^T
      return Contribution{{{Op::S, &r.G, 1.}, {Op::S, &r.G_t, c}, {Op::SDM, &r.G_t, 1.}},
                          {{Op::M, &r.G_t, 1.}},
                          {{Op::M, &r.G, 1.}}};
    // mu: c S^-1 G^T + S^-1 D M^-1 G^T; B1 = G^T
    return Contribution{{{Op::S, &r.G, c}, {Op::SDM, &r.G, 1.}}, {{Op::M, &r.G, 1.}}, {}};
  };
  // The unknowns U that the rows touch, and each contribution restricted to U:
  // the functionals only read entries in U.
  std::vector<unsigned int> U;
  if (position_in_U.size() != n)
    position_in_U.assign(n, -1);
  for (const auto& r : rows)
    for (const SparseRow* row : {&r.G, &r.G_t, &r.G_tt})
      for (const unsigned int i : row->index)
        if (position_in_U[i] < 0)
        {
          position_in_U[i] = U.size();
          U.push_back(i);
        }
  struct Restricted
  {
    std::vector<double> q, b1, b2; ///< on U
  };
  auto restrict_terms = [&](const std::vector<Term>& terms, std::vector<double>& w)
  {
    w.assign(U.size(), 0.);
    for (const Term& t : terms)
      for (std::size_t k = 0; k < t.row->size(); ++k)
      {
        const double f = t.factor * t.row->value[k];
        if (f == 0.)
          continue;
        const dealii::Vector<double>& R = responses->response(t.row->index[k], t.op);
        for (std::size_t u = 0; u < U.size(); ++u)
          w[u] += f * R[U[u]];
      }
  };
  auto on_U = [&](const SparseRow& l, const std::vector<double>& w)
  {
    double sum = 0.;
    for (std::size_t k = 0; k < l.size(); ++k)
      sum += l.value[k] * w[position_in_U[l.index[k]]];
    return sum;
  };
  std::vector<std::array<Restricted, 3>> restricted(m_all);
  std::vector<std::array<bool, 3>> restricted_done(m_all, {{false, false, false}});

  DynamicState x;
  x.t = t1;
  x.v.reinit(n);
  x.a.reinit(n);
  x.lambda.assign(m_all, 0.);
  std::vector<double> gaps(m_all);
  dealii::Vector<double> Minv_B1(n), Minv_B2(n);
  active_set.start(active_at_start);
  for (;;)
  {
    const auto& A = active_set.active_indices();
    const unsigned int m = A.size();
    small.reinit(3 * m, 3 * m);
    small_rhs.reinit(3 * m);
    small_solution.reinit(3 * m);
    for (unsigned int l = 0; l < m; ++l)
      for (unsigned int kind = 0; kind < 3; ++kind)
      {
        Restricted& w = restricted[A[l]][kind];
        if (!restricted_done[A[l]][kind])
        {
          const Contribution col = contribution(A[l], kind);
          restrict_terms(col.q, w.q);
          restrict_terms(col.b1, w.b1);
          restrict_terms(col.b2, w.b2);
          restricted_done[A[l]][kind] = true;
        }
        for (unsigned int k = 0; k < m; ++k)
          for (unsigned int level = 0; level < 3; ++level)
          {
            const Functionals& f = F[A[k]];
            small(level * m + k, kind * m + l) = on_U(f.Lq[level], w.q) -
                                                 on_U(f.L1[level], w.b1) -
                                                 on_U(f.L2[level], w.b2);
          }
      }
    for (unsigned int k = 0; k < m; ++k)
      for (unsigned int level = 0; level < 3; ++level)
        small_rhs(level * m + k) = -F[A[k]].base[level];
    solve_multiplier_system(small, small_rhs, small_solution, t1, "BDF step");
    // Coefficients of the cached responses, then one vector update per response:
    // q = q0 + S^-1 (..) + S^-1 D M^-1 (..), M^-1 B1, M^-1 B2.
    std::vector<double> coefficient_S(U.size(), 0.), coefficient_SDM(U.size(), 0.),
        coefficient_B1(U.size(), 0.), coefficient_B2(U.size(), 0.);
    std::fill(x.lambda.begin(), x.lambda.end(), 0.);
    auto accumulate = [&](const std::vector<Term>& terms, double y, bool b1, bool b2)
    {
      for (const Term& t : terms)
        for (std::size_t k = 0; k < t.row->size(); ++k)
        {
          const std::size_t u = position_in_U[t.row->index[k]];
          const double value = y * t.factor * t.row->value[k];
          if (b1)
            coefficient_B1[u] += value;
          else if (b2)
            coefficient_B2[u] += value;
          else if (t.op == Op::S)
            coefficient_S[u] += value;
          else
            coefficient_SDM[u] += value;
        }
    };
    for (unsigned int l = 0; l < m; ++l)
      for (unsigned int kind = 0; kind < 3; ++kind)
      {
        const double y = small_solution(kind * m + l);
        const Contribution col = contribution(A[l], kind);
        accumulate(col.q, y, false, false);
        accumulate(col.b1, y, true, false);
        accumulate(col.b2, y, false, true);
        if (kind == 0)
          x.lambda[A[l]] = y;
      }
    x.q = q0;
    Minv_B1 = 0.;
    Minv_B2 = 0.;
    double* __restrict q = x.q.begin();
    double* __restrict b1 = Minv_B1.begin();
    double* __restrict b2 = Minv_B2.begin();
    for (std::size_t u = 0; u < U.size(); ++u)
    {
      const double* __restrict rs = responses->response(U[u], Op::S).begin();
      const double* __restrict rt = responses->response(U[u], Op::SDM).begin();
      const double* __restrict rm = responses->response(U[u], Op::M).begin();
      const double alpha = coefficient_S[u], beta = coefficient_SDM[u],
                   gamma = coefficient_B1[u], delta = coefficient_B2[u];
      if (alpha != 0. || beta != 0.)
        for (unsigned int i = 0; i < n; ++i)
          q[i] += alpha * rs[i] + beta * rt[i];
      if (gamma != 0. || delta != 0.)
        for (unsigned int i = 0; i < n; ++i)
        {
          b1[i] += gamma * rm[i];
          b2[i] += delta * rm[i];
        }
    }
    // v = c q - rho_q - M^-1 B1, a = c v - rho_v - M^-1 B2.
    x.v.equ(c, x.q);
    x.v -= rho_q;
    x.v -= Minv_B1;
    x.a.equ(c, x.v);
    x.a -= rho_v;
    x.a -= Minv_B2;
    for (unsigned int i = 0; i < m_all; ++i)
      gaps[i] = rows[i].position_residual(x.q);
    if (active_set.accept(gaps, x.lambda, t1, step_number + 1))
      break;
    ++stats.active_set_iterations;
  }
  for (const unsigned int i : U)
    position_in_U[i] = -1;
  stats.active_set_changes += active_set.changes_in_step();
  x.active = active_set.active();
  return x;
}
} // namespace pantocat
