#include <pantocat/base/input_error.h>
#include <pantocat/time/dynamic_state_serialization.h>
#include <pantocat/time/generalized_alpha_integrator.h>
#include <pantocat/time/multiplier_system.h>

namespace pantocat
{
namespace
{
/// Columns of the S batch: X = S^-1 G^T and, for the owner, the base solution.
constexpr unsigned int lambda_column = 0, base_column = IterationMatrix::base_column;
} // namespace

GeneralizedAlphaIntegrator::Coefficients::Coefficients(const double rho)
    : alpha_m((2. * rho - 1.) / (rho + 1.)), alpha_f(rho / (rho + 1.)),
      beta(0.25 * (1. - alpha_m + alpha_f) * (1. - alpha_m + alpha_f)),
      gamma(0.5 - alpha_m + alpha_f)
{
}

GeneralizedAlphaIntegrator::GeneralizedAlphaIntegrator(
    const SemiDiscreteSystem& system, const double time_step, const double rho_infinity,
    const unsigned int max_iterations, const LinearSolverType linear_solver)
    : TimeIntegrator(system), h(time_step), k(rho_infinity),
      c_q((1. - k.alpha_m) / ((1. - k.alpha_f) * k.beta * h * h)),
      c_v(k.gamma / (k.beta * h)),
      S(system, c_v, c_q, "generalized-alpha iteration matrix K + c_v D + c_q M",
        linear_solver),
      operators(system), at_next(system), active_set(system, max_iterations, false)
{
  mass_inverse.initialize(system.mass, system.mass_is_diagonal, "mass matrix M",
                          linear_solver);
}

void GeneralizedAlphaIntegrator::initialize(const DynamicState& initial)
{
  current = initial;
  pseudo_acceleration = initial.a; // a_0 = a_c,0 (Arnold and Bruels)
  step_number = 0;
}

void GeneralizedAlphaIntegrator::compute_columns(const unsigned int l,
                                                 const ConstraintState& r)
{
  InterleavedColumns &X = S.S_columns[l], &U = S.M_columns[l];
  for (unsigned int i = 0; i < X.size(); ++i) // keep the base column
    X(i, lambda_column) = 0.;
  U.clear();
  X.add_row(lambda_column, r.G, 1.);
  U.add_row(0, r.G, 1.);
  if (const SparseDirectSolver* M = mass_inverse.factorised())
    S.inverse.solve_interleaved_with(X.data(), *M, U.data());
  else
  {
    S.inverse.solve_interleaved(X.data(), InterleavedColumns::width);
    mass_inverse.apply(U);
  }
}

void GeneralizedAlphaIntegrator::advance()
{
  const unsigned int n = system.n_dofs(), m_all = system.n_constraints();
  const double t1 = current.t + h;
  const auto& rows = at_next.at(t1, 1);
  if (!S.fixed_columns_ready)
  {
    for (const unsigned int l : S.fixed)
      compute_columns(l, rows[l]);
    S.fixed_columns_ready = true;
  }
  // Predictors: q^ = q_n + h v_n + h^2 (1/2 - beta) a_n, v^ = v_n + h (1 - gamma) a_n,
  // w = (alpha_m a_n - alpha_f a_c,n) / (1 - alpha_f). Then
  // S q0 = f + M (c_q q^ - w) + D (c_v q^ - v^).
  const dealii::Vector<double>& a_n = pseudo_acceleration;
  dealii::Vector<double> q_hat(current.q), v_hat(current.v), w(n), mass_part(n),
      damping_part(n);
  q_hat.add(h, current.v, h * h * (0.5 - k.beta), a_n);
  v_hat.add(h * (1. - k.gamma), a_n);
  w.equ(k.alpha_m / (1. - k.alpha_f), a_n);
  w.add(-k.alpha_f / (1. - k.alpha_f), current.a);
  mass_part.equ(c_q, q_hat);
  mass_part -= w;
  damping_part.equ(c_v, q_hat);
  damping_part -= v_hat;
  InterleavedColumns& B = S.base_batch();
  operators.set_time(t1);
  operators.history(mass_part, damping_part, B, base_column);
  if (S.moving.empty())
    S.inverse.solve_interleaved(B.data(), InterleavedColumns::width);
  for (const unsigned int l : S.moving)
    compute_columns(l, rows[l]);

  // G_k X_l and the base gaps; for the compliant constraints also the rates
  // dg/dt = G_t q + G v + z_t with v = v^ + c_v (q - q^) (Newmark), i.e.
  // (G_t + c_v G) X_l per unit lambda_l and the base rate of q0.
  std::vector<double> GX(m_all * m_all), base_gap(m_all), RX(m_all * m_all),
      base_rate(m_all);
  for (unsigned int i = 0; i < m_all; ++i)
  {
    base_gap[i] = B.dot(rows[i].G, base_column) + rows[i].z;
    for (unsigned int l = 0; l < m_all; ++l)
      GX[i * m_all + l] = S.S_columns[l].dot(rows[i].G, lambda_column);
    if (!system.constraints[i]->is_compliant())
      continue;
    base_rate[i] = B.dot(rows[i].G_t, base_column) +
                   c_v * (base_gap[i] - rows[i].z - rows[i].G.dot(q_hat)) +
                   rows[i].G.dot(v_hat) + rows[i].z_t;
    for (unsigned int l = 0; l < m_all; ++l)
      RX[i * m_all + l] =
          S.S_columns[l].dot(rows[i].G_t, lambda_column) + c_v * GX[i * m_all + l];
  }

  DynamicState x;
  x.t = t1;
  x.lambda.assign(m_all, 0.);
  std::vector<double> gaps(m_all), rates(m_all);
  active_set.start(current.active);
  for (;;)
  {
    // Unknowns: the multipliers of the active rigid constraints (rows g = 0)
    // and the forces of the engaged compliant ones, whose rows are their
    // law divided by k: lambda/k + g + (c/k) dg/dt = 0 at t_{n+1}, i.e.
    // (G S^-1 G^T + C) lambda = -g0 with the compliance C = diag(1/k) (and the
    // damping part): implicit in the force, S untouched.
    unknowns = active_set.active_indices();
    const auto& E = active_set.engaged_indices();
    unknowns.insert(unknowns.end(), E.begin(), E.end());
    const auto& U = unknowns;
    const unsigned int m = U.size();
    small.reinit(m, m);
    small_rhs.reinit(m);
    small_solution.reinit(m);
    for (unsigned int i = 0; i < m; ++i)
    {
      const Constraint& c = *system.constraints[U[i]];
      const double damping =
          c.is_compliant() ? c.compliance().damping / c.compliance().stiffness : 0.;
      for (unsigned int l = 0; l < m; ++l)
        small(i, l) = GX[U[i] * m_all + U[l]] + damping * RX[U[i] * m_all + U[l]];
      if (c.is_compliant())
        small(i, i) += 1. / c.compliance().stiffness;
      small_rhs(i) = -(base_gap[U[i]] + damping * base_rate[U[i]]);
    }
    solve_multiplier_system(small, small_rhs, small_solution, t1,
                            "generalized-alpha step");
    std::fill(x.lambda.begin(), x.lambda.end(), 0.);
    for (unsigned int l = 0; l < m; ++l)
      x.lambda[U[l]] = small_solution(l);
    for (unsigned int i = 0; i < m_all; ++i)
    {
      gaps[i] = base_gap[i];
      rates[i] = base_rate[i];
      for (unsigned int l = 0; l < m; ++l)
      {
        gaps[i] += small_solution(l) * GX[i * m_all + U[l]];
        rates[i] += small_solution(l) * RX[i * m_all + U[l]];
      }
    }
    if (active_set.accept(gaps, x.lambda, t1, step_number + 1, rates))
      break;
    ++stats.active_set_iterations;
  }
  stats.active_set_changes += active_set.changes_in_step();
  x.active = active_set.active();
  const auto& A = active_set.active_indices();

  // q = q0 + sum_l lambda_l X_l, then a, v, a_c from the Newmark relations.
  x.q.reinit(n);
  if (S.moving.empty())
    B.add_combination({{0., 0., 0., 1.}}, x.q);
  for (unsigned int l = 0; l < m_all; ++l)
    if (x.active[l] || l == S.base_owner)
      S.S_columns[l].add_combination({{x.lambda[l], 0., 0., l == S.base_owner ? 1. : 0.}},
                                     x.q);
  clamp_compliant_forces(system, x.lambda);
  dealii::Vector<double> a_next(x.q);
  a_next.add(-1., q_hat);
  a_next *= 1. / (h * h * k.beta);
  x.v = v_hat;
  x.v.add(h * k.gamma, a_next);
  x.a.reinit(n, true);
  x.a.equ((1. - k.alpha_m) / (1. - k.alpha_f), a_next);
  x.a += w;

  // Velocity projection onto dg/dt = 0 of the active set: v += M^-1 G^T eta.
  const unsigned int m = A.size();
  if (m > 0)
  {
    small.reinit(m, m);
    small_rhs.reinit(m);
    small_solution.reinit(m);
    for (unsigned int i = 0; i < m; ++i)
    {
      const ConstraintState& r = rows[A[i]];
      for (unsigned int l = 0; l < m; ++l)
        small(i, l) = S.M_columns[A[l]].dot(r.G, 0);
      small_rhs(i) = -r.velocity_residual(x.q, x.v);
    }
    solve_multiplier_system(small, small_rhs, small_solution, t1, "velocity projection");
    for (unsigned int l = 0; l < m; ++l)
      S.M_columns[A[l]].add_combination({{small_solution(l), 0., 0., 0.}}, x.v);
  }
  pseudo_acceleration.swap(a_next);
  current = std::move(x);
  ++step_number;
  ++stats.steps;
}

void GeneralizedAlphaIntegrator::save(CheckpointOut& archive) const
{
  archive << step_number << current << pseudo_acceleration;
  save_statistics(archive);
}

void GeneralizedAlphaIntegrator::load(CheckpointIn& archive)
{
  archive >> step_number >> current >> pseudo_acceleration;
  load_statistics(archive);
  check_loaded(current, "x_n");
  check_loaded(pseudo_acceleration, system.n_dofs(), "the pseudo-acceleration a_n");
  check_loaded_steps(step_number);
}

IntegratorEntry GeneralizedAlphaIntegrator::registry_entry()
{
  IntegratorEntry e;
  e.name = "generalized-alpha";
  e.description = "the Chung-Hulbert method for the constrained second-order system "
                  "(Arnold-Bruels form, positions on the constraints, velocities "
                  "projected onto the hidden constraints)";
  e.explicit_step_limit = false;
  e.writes_checkpoints = true;
  e.locates_events = false;
  e.create = [](const SemiDiscreteSystem& system, const TimeIntegrationParameters& p)
  {
    return std::make_unique<GeneralizedAlphaIntegrator>(
        system, p.time_step, p.rho_infinity, p.max_active_set_iterations,
        p.linear_solver);
  };
  return e;
}
} // namespace pantocat
