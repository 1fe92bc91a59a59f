#include <pantocat/time/bdf2_integrator.h>
#include <pantocat/time/dynamic_state_serialization.h>
#include <pantocat/time/multiplier_system.h>

#include <array>

namespace pantocat
{
namespace
{
using Levels = std::array<double, 3>;

/**
 * The rows g, dg/dt, d2g/dt2 of a constraint applied to a solution with
 * positions X, velocities c X - U1 and accelerations c (c X - U1) - U2, from
 * the dot products of the rows G, G_t, G_tt with X, U1 and U2: the
 * functionals of the multiplier system.
 */
Levels functionals(const double c, const double GX, const double GtX, const double GttX,
                   const double GU1, const double GtU1, const double GU2)
{
  const double Gv = c * GX - GU1, Gtv = c * GtX - GtU1, Ga = c * Gv - GU2;
  return {{GX, GtX + Gv, GttX + 2. * Gtv + Ga}};
}

/// Multiplier kinds: the columns of one constraint in its S batch, in the
/// order of the multiplier system; the fourth column holds the base solution.
enum Column : unsigned int
{
  lambda = 0,
  eta = 1,
  mu = 2,
  base = IterationMatrix::base_column
};
/// Columns of the M batch: Y = M^-1 G^T, Z = M^-1 G_t^T.
enum MassColumn : unsigned int
{
  Y = 0,
  Z = 1
};
} // namespace

/// The block solver for one c: S = K + c D + c^2 M and the constraint columns.
struct Bdf2Integrator::Stage : IterationMatrix
{
  Stage(const SemiDiscreteSystem& system, const MassInverse& mass_inverse,
        const DampingOverMass& damping_over_mass, double c, LinearSolverType solver)
      : IterationMatrix(system, c, c * c, "BDF iteration matrix K + c D + c^2 M", solver),
        system(system), mass_inverse(mass_inverse), damping_over_mass(damping_over_mass),
        c(c)
  {
  }

  /**
   * The columns of constraint @p l for its rows @p r: the S batch
   * (X^lambda, X^eta, X^mu, and the base solution if l owns it; its right-hand
   * side must already be in column `base`) and the M batch (Y, Z).
   */
  void compute_columns(const unsigned int l, const ConstraintState& r)
  {
    const unsigned int n = system.n_dofs();
    InterleavedColumns &X = columns_of(l, S_columns, all_S),
                       &U = columns_of(l, M_columns, all_M);
    for (unsigned int i = 0; i < n; ++i) // keep the base column
      X(i, lambda) = X(i, eta) = X(i, mu) = 0.;
    U.clear();
    U.add_row(Y, r.G, 1.);
    U.add_row(Z, r.G_t, 1.);
    // X^lambda = G^T, X^eta = G^T + c G_t^T + D Z, X^mu = c G^T + D Y before
    // S^-1, with D Z = D M^-1 G_t^T and D Y = D M^-1 G^T sparse where the
    // bodies allow it (DampingOverMass), else from Y and Z on full vectors.
    const bool sparse_damping =
        damping_over_mass.apply(r.G, DY) && damping_over_mass.apply(r.G_t, DZ);
    if (sparse_damping)
    {
      X.add_row(eta, DZ, 1.);
      X.add_row(mu, DY, 1.);
    }
    else
      add_damping_of_mass_columns(X, U);
    X.add_row(lambda, r.G, 1.);
    X.add_row(eta, r.G, 1.);
    X.add_row(eta, r.G_t, c);
    X.add_row(mu, r.G, c);
    // Independent right-hand sides: S and M substitute side by side.
    const SparseDirectSolver* M = mass_inverse.factorised();
    if (sparse_damping && M)
      inverse.solve_interleaved_with(X.data(), *M, U.data());
    else
    {
      inverse.solve_interleaved(X.data(), InterleavedColumns::width);
      if (sparse_damping)
        mass_inverse.apply(U);
    }
  }

  /// X^mu += D M^-1 G^T and X^eta += D M^-1 G_t^T on full vectors (U <- M^-1 U).
  void add_damping_of_mass_columns(InterleavedColumns& X, InterleavedColumns& U) const
  {
    const unsigned int n = system.n_dofs();
    mass_inverse.apply(U);
    dealii::Vector<double> u(n), Du(n);
    for (const unsigned int k : {Y, Z})
    {
      for (unsigned int i = 0; i < n; ++i)
        u[i] = U(i, k);
      system.damping.vmult(Du, u);
      for (unsigned int i = 0; i < n; ++i)
        X(i, k == Y ? mu : eta) += Du[i];
    }
  }

  /// The batch of constraint l: the moving constraints' from IterationMatrix.
  InterleavedColumns& columns_of(const unsigned int l,
                                 std::vector<InterleavedColumns>& moving_batches,
                                 std::vector<InterleavedColumns>& fixed_batches)
  {
    if (system.constraints[l]->depends_on_time())
      return moving_batches[position[l]];
    if (fixed_batches.size() != system.n_constraints())
      fixed_batches.resize(system.n_constraints());
    if (fixed_batches[l].size() != system.n_dofs())
      fixed_batches[l].reinit(system.n_dofs());
    return fixed_batches[l];
  }
  const InterleavedColumns& S_of(const unsigned int l)
  {
    return columns_of(l, S_columns, all_S);
  }
  const InterleavedColumns& M_of(const unsigned int l)
  {
    return columns_of(l, M_columns, all_M);
  }

  const SemiDiscreteSystem& system;
  const MassInverse& mass_inverse;
  const DampingOverMass& damping_over_mass;
  double c;
  SparseRow DY, DZ; ///< workspace
  std::vector<InterleavedColumns> all_S, all_M;
  bool fixed_columns_ready = false;
  unsigned int base_owner() const
  {
    return moving.empty() ? system.n_constraints() : moving.front();
  }
};

Bdf2Integrator::Bdf2Integrator(const SemiDiscreteSystem& system, const double time_step,
                               const unsigned int max_iterations,
                               const LinearSolverType linear_solver)
    : TimeIntegrator(system), dt(time_step), linear_solver(linear_solver),
      damping_over_mass(system), operators(system), at_next(system),
      active_set(system, max_iterations)
{
  mass_inverse.initialize(system.mass, system.mass_is_diagonal, "mass matrix M",
                          linear_solver);
}

Bdf2Integrator::~Bdf2Integrator() = default;

DynamicState Bdf2Integrator::implicit_step(Stage& s, const dealii::Vector<double>& rho_q,
                                           const dealii::Vector<double>& rho_v,
                                           const double t1,
                                           const std::vector<bool>& active_at_start)
{
  const unsigned int n = system.n_dofs(), m_all = system.n_constraints();
  const double c = s.c;
  const auto& rows = at_next.at(t1);
  if (!s.fixed_columns_ready)
  {
    for (const unsigned int l : s.fixed)
      s.compute_columns(l, rows[l]);
    s.fixed_columns_ready = true;
  }
  // Base solution S^-1 (f + M (rho_v + c rho_q) + D rho_q), solved in one
  // batch with the columns of the first moving constraint.
  dealii::Vector<double> history(rho_v);
  history.add(c, rho_q);
  operators.set_time(t1);
  operators.history(history, rho_q, s.base_batch(), IterationMatrix::base_column);
  if (s.moving.empty())
    s.inverse.solve_interleaved(s.base_only.data(), InterleavedColumns::width);
  for (const unsigned int l : s.moving)
    s.compute_columns(l, rows[l]);
  const InterleavedColumns& B = s.base_batch();

  // Functionals of the base solution and of every column on every row.
  std::vector<Levels> base_levels(m_all);
  std::vector<std::array<Levels, 3>> F(m_all * m_all); // [k * m_all + l][kind]
  for (unsigned int k = 0; k < m_all; ++k)
  {
    const ConstraintState& r = rows[k];
    base_levels[k] =
        functionals(c, B.dot(r.G, base), B.dot(r.G_t, base), B.dot(r.G_tt, base),
                    r.G.dot(rho_q), r.G_t.dot(rho_q), r.G.dot(rho_v));
    base_levels[k][0] += r.z;
    base_levels[k][1] += r.z_t;
    base_levels[k][2] += r.z_tt;
    for (unsigned int l = 0; l < m_all; ++l)
    {
      const InterleavedColumns &X = s.S_of(l), &U = s.M_of(l);
      const double GY = U.dot(r.G, Y), GtY = U.dot(r.G_t, Y), GZ = U.dot(r.G, Z),
                   GtZ = U.dot(r.G_t, Z);
      for (const unsigned int kind : {lambda, eta, mu})
        F[k * m_all + l][kind] =
            functionals(c, X.dot(r.G, kind), X.dot(r.G_t, kind), X.dot(r.G_tt, kind),
                        kind == eta  ? GZ
                        : kind == mu ? GY
                                     : 0.,
                        kind == eta  ? GtZ
                        : kind == mu ? GtY
                                     : 0.,
                        kind == eta ? GY : 0.);
    }
  }

  // Active-set iteration (Sec. 5.3) on the multiplier system alone.
  DynamicState x;
  x.t = t1;
  x.lambda.assign(m_all, 0.);
  std::vector<double> gaps(m_all), rates(m_all);
  active_set.start(active_at_start);
  // Unknowns: lambda of the constraints with force, eta and mu of all that
  // hold, lambda of the engaged compliant ones; rows: g and dg/dt of all that
  // hold, d2g/dt2 of those with force (a touching constraint has
  // g^(II) := lambda = 0, ActiveSetIteration), and the force law of each
  // engaged compliant constraint (Constraint::is_compliant) divided by k,
  //
  //   lambda_l / k_l + g_l(t_{n+1}) + (c_l / k_l) dg_l/dt(t_{n+1}) = 0,
  //
  // whose g and dg/dt are the level-0 and level-1 functionals of the same
  // columns: the compliance 1/k on the diagonal of the Schur complement
  // (G S^-1 G^T + C) lambda = ..., the implicit force without touching S.
  struct Entry
  {
    unsigned int constraint, kind_or_level;
  };
  constexpr unsigned int force_law = 3; // equation kind of an engaged spring
  std::vector<Entry> unknowns, equations;
  std::vector<double> y_lambda(m_all), y_eta(m_all), y_mu(m_all);
  for (;;)
  {
    const auto &A = active_set.active_indices(), &A_force = active_set.force_indices();
    unknowns.clear();
    equations.clear();
    for (const unsigned int l : A_force)
      unknowns.push_back({l, lambda}), equations.push_back({l, 2});
    for (const unsigned int l : active_set.engaged_indices())
      unknowns.push_back({l, lambda}), equations.push_back({l, force_law});
    for (const unsigned int l : A)
    {
      unknowns.push_back({l, eta});
      unknowns.push_back({l, mu});
      equations.push_back({l, 0});
      equations.push_back({l, 1});
    }
    const unsigned int size = unknowns.size();
    small.reinit(size, size);
    small_rhs.reinit(size);
    small_solution.reinit(size);
    for (unsigned int r = 0; r < size; ++r)
    {
      const Entry& e = equations[r];
      const auto entry = [&](const Entry& u, const unsigned int level)
      { return F[e.constraint * m_all + u.constraint][u.kind_or_level][level]; };
      if (e.kind_or_level == force_law)
      {
        const Compliance& law = system.constraints[e.constraint]->compliance();
        const double damping = law.damping / law.stiffness;
        for (unsigned int c = 0; c < size; ++c)
          small(r, c) = entry(unknowns[c], 0) + damping * entry(unknowns[c], 1) +
                        (unknowns[c].constraint == e.constraint &&
                                 unknowns[c].kind_or_level == lambda
                             ? 1. / law.stiffness
                             : 0.);
        small_rhs(r) =
            -(base_levels[e.constraint][0] + damping * base_levels[e.constraint][1]);
        continue;
      }
      for (unsigned int c = 0; c < size; ++c)
        small(r, c) = entry(unknowns[c], e.kind_or_level);
      small_rhs(r) = -base_levels[e.constraint][e.kind_or_level];
    }
    solve_multiplier_system(small, small_rhs, small_solution, t1, "BDF step");
    std::fill(y_lambda.begin(), y_lambda.end(), 0.);
    std::fill(y_eta.begin(), y_eta.end(), 0.);
    std::fill(y_mu.begin(), y_mu.end(), 0.);
    for (unsigned int c = 0; c < size; ++c)
    {
      const Entry& u = unknowns[c];
      (u.kind_or_level == lambda ? y_lambda
       : u.kind_or_level == eta  ? y_eta
                                 : y_mu)[u.constraint] = small_solution(c);
    }
    x.lambda = y_lambda;
    for (unsigned int k = 0; k < m_all; ++k)
    {
      gaps[k] = base_levels[k][0];
      rates[k] = base_levels[k][1];
      for (unsigned int c = 0; c < size; ++c)
      {
        const auto& f = F[k * m_all + unknowns[c].constraint][unknowns[c].kind_or_level];
        gaps[k] += small_solution(c) * f[0];
        rates[k] += small_solution(c) * f[1];
      }
    }
    if (active_set.accept(gaps, x.lambda, t1, step_number + 1, rates))
      break;
    ++stats.active_set_iterations;
  }
  stats.active_set_changes += active_set.changes_in_step();
  x.active = active_set.active();
  clamp_compliant_forces(system, x.lambda);

  // The accepted step's vectors:
  //   q = base + sum_l lambda_l X^lambda_l + eta_l X^eta_l + mu_l X^mu_l,
  //   v = c q - rho_q - sum_l (mu_l Y_l + eta_l Z_l),  a = c v - rho_v - sum_l eta_l Y_l.
  const auto& A = active_set.active_indices();
  // One pass over the unknowns, reading the interleaved columns in place.
  std::vector<std::pair<const double*, std::array<double, 4>>> q_terms, u_terms;
  if (s.moving.empty())
    q_terms.push_back({B.data(), {{0., 0., 0., 1.}}});
  for (unsigned int l = 0; l < m_all; ++l)
    if (x.active[l] || l == s.base_owner())
      q_terms.push_back(
          {s.S_of(l).data(),
           {{y_lambda[l], y_eta[l], y_mu[l], l == s.base_owner() ? 1. : 0.}}});
  for (const unsigned int l : A) // (mu Y + eta Z, eta Y) of constraint l
    u_terms.push_back({s.M_of(l).data(), {{y_mu[l], y_eta[l], y_eta[l], 0.}}});
  x.q.reinit(n, true);
  x.v.reinit(n, true);
  x.a.reinit(n, true);
  constexpr unsigned int w = InterleavedColumns::width;
  for (unsigned int i = 0; i < n; ++i)
  {
    double q = 0., u1 = 0., u2 = 0.;
    for (const auto& [X, f] : q_terms)
      q += f[0] * X[w * i] + f[1] * X[w * i + 1] + f[2] * X[w * i + 2] +
           f[3] * X[w * i + 3];
    for (const auto& [U, f] : u_terms)
    {
      u1 += f[0] * U[w * i + Y] + f[1] * U[w * i + Z];
      u2 += f[2] * U[w * i + Y];
    }
    x.q[i] = q;
    x.v[i] = c * q - rho_q[i] - u1;
    x.a[i] = c * x.v[i] - rho_v[i] - u2;
  }
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
  Stage full(system, mass_inverse, damping_over_mass, 1. / dt, linear_solver),
      half(system, mass_inverse, damping_over_mass, 2. / dt, linear_solver);
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
    clamp_compliant_forces(system, fine.lambda);
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
      bdf2 = std::make_unique<Stage>(system, mass_inverse, damping_over_mass, 1.5 / dt,
                                     linear_solver);
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

void Bdf2Integrator::save(CheckpointOut& archive) const
{
  archive << step_number << previous << current;
  save_statistics(archive);
}

void Bdf2Integrator::load(CheckpointIn& archive)
{
  archive >> step_number >> previous >> current;
  load_statistics(archive);
  check_loaded(previous, "x_{n-1}");
  check_loaded(current, "x_n");
  check_loaded_steps(step_number);
}

IntegratorEntry Bdf2Integrator::registry_entry()
{
  IntegratorEntry e;
  e.name = "bdf2";
  e.description =
      "two-step BDF on the stabilised index-2 formulation (38) with a Richardson start";
  e.explicit_step_limit = false;
  e.writes_checkpoints = true;
  e.locates_events = false;
  e.create = [](const SemiDiscreteSystem& system, const TimeIntegrationParameters& p)
  {
    return std::make_unique<Bdf2Integrator>(system, p.time_step,
                                            p.max_active_set_iterations, p.linear_solver);
  };
  return e;
}
} // namespace pantocat
