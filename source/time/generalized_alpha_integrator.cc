#include <pantocat/base/input_error.h>
#include <pantocat/time/dynamic_state_serialization.h>
#include <pantocat/time/generalized_alpha_integrator.h>
#include <pantocat/constrained_fast/multiplier_system.h>

#include <tuple>

namespace pantocat
{
namespace
{
/// Columns of the S batch: S^-1 G^T, S^-1 G_t^T.
constexpr unsigned int lambda_column = 0, rate_column = 1;

/// The factors of predict().
struct PredictorFactors
{
  double h, hq, hv, wm, wf, c_q, c_v;
};

/// The predictor q^ = q + h v + hq a_n of one unknown (every pass and dot
/// product forms it so: the same bits).
inline double q_hat(const PredictorFactors& f, const double q, const double v,
                    const double a_n)
{
  return q + f.h * v + f.hq * a_n;
}
/// The predictor v^ = v + hv a_n of one unknown.
inline double v_hat(const PredictorFactors& f, const double v, const double a_n)
{
  return v + f.hv * a_n;
}
/// w = wm a_n + wf a of one unknown.
inline double w_of(const PredictorFactors& f, const double a_n, const double a)
{
  return f.wm * a_n + f.wf * a;
}

/**
 * The right-hand side's parts r = c_q q^ - w + mu (c_v q^ - v^) (the damping
 * split of PatternOperators: mu of the rows' block) and c_v q^ - v^ from the
 * predictors q^, v^, w, in one pass; the predictors are not stored
 * (newmark_update() forms them again). Compiled for AVX2 beside the
 * baseline, without fused multiply-add: the same bits either way.
 */
__attribute__((target_clones("avx2", "default"))) void
predict(const unsigned int n, const PredictorFactors f, const double mu,
        const double* __restrict q, const double* __restrict v,
        const double* __restrict a_n, const double* __restrict a,
        double* __restrict mass_part, double* __restrict damping_part)
{
  for (unsigned int i = 0; i < n; ++i)
  {
    const double qh = q_hat(f, q[i], v[i], a_n[i]);
    const double dp = f.c_v * qh - v_hat(f, v[i], a_n[i]);
    mass_part[i] = f.c_q * qh - w_of(f, a_n[i], a[i]) + mu * dp;
    damping_part[i] = dp;
  }
}

/// G q^ and G v^ of a constraint's row, summed as SparseRow::dot() sums them.
std::pair<double, double> predicted_dots(const SparseRow& G, const PredictorFactors& f,
                                         const double* q, const double* v,
                                         const double* a_n)
{
  double gq = 0., gv = 0.;
  for (std::size_t k = 0; k < G.index.size(); ++k)
  {
    const unsigned int j = G.index[k];
    gq += G.value[k] * q_hat(f, q[j], v[j], a_n[j]);
    gv += G.value[k] * v_hat(f, v[j], a_n[j]);
  }
  return {gq, gv};
}

/**
 * The Newmark relations in one pass: a_next = (q - q^) fa, v = v^ + fv
 * a_next, a = fw a_next + w, with the predictors q^, v^, w formed again from
 * the state x_n (q_n, v_n, a_n, a_c,n) as predict() formed them (AVX2 beside
 * the baseline, the same bits).
 */
__attribute__((target_clones("avx2", "default"))) void
newmark_update(const unsigned int n, const PredictorFactors f, const double fa,
               const double fv, const double fw, const double* __restrict q,
               const double* __restrict q_n, const double* __restrict v_n,
               const double* __restrict a_n, const double* __restrict a_c,
               double* __restrict a_next, double* __restrict v, double* __restrict a)
{
  for (unsigned int i = 0; i < n; ++i)
  {
    const double ai = (q[i] + -1. * q_hat(f, q_n[i], v_n[i], a_n[i])) * fa;
    a_next[i] = ai;
    v[i] = v_hat(f, v_n[i], a_n[i]) + fv * ai;
    a[i] = fw * ai + w_of(f, a_n[i], a_c[i]);
  }
}
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
      operators(system, {c_q, c_v, 1.}), at_next(system),
      active_set(system, max_iterations, ActiveSetIteration::ClosingConstraint::touching),
      impacts(system, mass_inverse)
{
  mass_inverse.initialize(system.mass, system.mass_is_diagonal, "mass matrix M",
                          linear_solver);
  for (const auto& c : system.constraints)
  {
    with_rate.push_back(c->is_compliant());
    ratio.push_back(damping_ratio(*c));
  }
}

void GeneralizedAlphaIntegrator::initialize(const DynamicState& initial)
{
  current = initial;
  current.impulse.clear();
  pseudo_acceleration = initial.a; // a_0 = a_c,0 (Arnold and Bruels)
  step_number = 0;
}

void GeneralizedAlphaIntegrator::compute_moving_columns(const unsigned int c,
                                                        const ConstraintState& r)
{
  LocalColumns &X = S.S_columns[c], &U = S.M_columns[c];
  X.clear();
  U.clear();
  X.add_row(lambda_column, r.G, 1.);
  X.add_row(rate_column, r.G_t, 1.);
  U.add_row(0, r.G, 1.);
  X.solve(S.inverse);
  mass_inverse.apply(U);
}

void GeneralizedAlphaIntegrator::initialize_fixed(
    const std::vector<ConstraintState>& rows)
{
  // A fixed compliant row, lambda/k + g + d dg/dt = 0 with dg/dt = G v =
  // G v^ + c_v G (q - q^) (G_t = 0), is (1 + d c_v) times
  // G S^-1 G^T lambda + lambda / (k (1 + d c_v)) = -(g0 + d r0) / (1 + d c_v):
  // divided by (1 + d c_v), the fixed block is symmetric with the
  // compliance 1 / (k (1 + d c_v)) on its diagonal.
  std::vector<const SparseRow*> G;
  std::vector<double> compliance;
  for (const unsigned int i : S.fixed)
  {
    if (rows[i].G_t.size() > 0 || rows[i].G_tt.size() > 0)
      throw SimulationError("constraint " + system.constraints[i]->name() +
                            " has constant rows but a time derivative");
    G.push_back(&rows[i].G);
    const Constraint& c = *system.constraints[i];
    compliance.push_back(
        c.is_compliant() ? 1. / (c.compliance().stiffness * (1. + damping_ratio(c) * c_v))
                         : 0.);
  }
  fixed_S.initialize(G, S.inverse, system.n_dofs(),
                     "matrix G S^-1 G^T + C of the fixed constraints (generalized-alpha)",
                     compliance);
  fixed_M.initialize(G, mass_inverse, system.n_dofs(),
                     "matrix G M^-1 G^T of the fixed constraints (velocity projection)");
  keep.assign(S.fixed.size(), false);
  factors.assign(S.fixed.size(), 0.);
  fixed_G.clear();
  for (const unsigned int i : S.fixed)
    fixed_G.push_back(rows[i].G);
  fixed_at_row.build(fixed_G, system.n_dofs());
  seen.assign(S.fixed.size(), 0);
  fixed_ready = true;
}

void GeneralizedAlphaIntegrator::advance()
{
  const unsigned int n = system.n_dofs(), m_all = system.n_constraints();
  const double t1 = current.t + h;
  const auto& rows = at_next.at(t1, 1);
  if (!fixed_ready)
    initialize_fixed(rows);
  // Predictors: q^ = q_n + h v_n + h^2 (1/2 - beta) a_n, v^ = v_n + h (1 - gamma) a_n,
  // w = (alpha_m a_n - alpha_f a_c,n) / (1 - alpha_f). Then
  // S q0 = f + M (c_q q^ - w) + D (c_v q^ - v^), formed with the damping
  // split (PatternOperators) as q0 = gamma (c_v q^ - v^) + S^-1 (f + M (c_q q^
  // - w + mu (c_v q^ - v^)) + E (c_v q^ - v^)). The predictors in one pass
  // per block.
  const dealii::Vector<double>& a_n = pseudo_acceleration;
  for (auto* x : {&mass_part, &damping_part})
    x->reinit(n, true);
  const PredictorFactors f{h,
                           h * h * (0.5 - k.beta),
                           h * (1. - k.gamma),
                           k.alpha_m / (1. - k.alpha_f),
                           -k.alpha_f / (1. - k.alpha_f),
                           c_q,
                           c_v};
  for (const PatternOperators::Shift& b : operators.shifts())
  {
    const unsigned int i = b.first;
    predict(b.last - i, f, b.mu, current.q.begin() + i, current.v.begin() + i,
            a_n.begin() + i, current.a.begin() + i, mass_part.begin() + i,
            damping_part.begin() + i);
  }
  operators.set_time(t1);
  operators.solve_history(mass_part, damping_part, S.inverse, S.base);
  for (unsigned int c = 0; c < S.moving.size(); ++c)
    compute_moving_columns(c, rows[S.moving[c]]);
  const dealii::Vector<double>& q0 = S.base; // the base solution

  // g and dg/dt of every constraint at q0, with v = v^ + c_v (q - q^) (Newmark).
  // G q^ and G v^ are kept for the trials' rates.
  base_gap.resize(m_all);
  base_rate.resize(m_all);
  G_q_hat.resize(m_all);
  G_v_hat.resize(m_all);
  // G y of constraint i (a fixed one's from the compressed copy, the same bits).
  const auto G_dot = [&](const unsigned int i, const dealii::Vector<double>& y)
  { return S.moves[i] ? rows[i].G.dot(y) : fixed_G.dot(S.position[i], y.begin()); };
  // (the rate of a rigid constraint enters nothing: its law has d = 0, and
  // accept() reads the rates of the compliant ones only)
  for (unsigned int i = 0; i < m_all; ++i)
  {
    const ConstraintState& r = rows[i];
    const double Gq0 = G_dot(i, q0);
    base_gap[i] = Gq0 + r.z;
    if (!with_rate[i])
    {
      G_q_hat[i] = G_v_hat[i] = base_rate[i] = 0.;
      continue;
    }
    std::tie(G_q_hat[i], G_v_hat[i]) =
        predicted_dots(r.G, f, current.q.begin(), current.v.begin(), a_n.begin());
    base_rate[i] = r.G_t.dot(q0) + c_v * (Gq0 - G_q_hat[i]) + G_v_hat[i] + r.z_t;
  }

  DynamicState x = std::move(spare); // its vectors' memory, if any
  x.t = t1;
  x.lambda.assign(m_all, 0.);
  x.impulse.clear();
  gaps.resize(m_all);
  rates.resize(m_all);
  active_set.start(current.active);
  bool touching = false;
  for (bool first_trial = true;; first_trial = false)
  {
    // The last trial took the base's vector: solved again, the same bits.
    if (!first_trial)
      operators.solve_history(mass_part, damping_part, S.inverse, S.base);
    solve_position_level(rows, x.lambda);
    assemble_positions(x.lambda, x.q);
    touching = active_set.force_indices().size() != active_set.active_indices().size();
    if (touching)
    {
      // Touching constraints hold by the position projection alone.
      q_newmark = x.q;
      project(
          rows, t1, [&](const unsigned int i) { return G_dot(i, x.q) + rows[i].z; }, x.q,
          position_multipliers, "position projection");
    }
    for (unsigned int i = 0; i < m_all; ++i)
    {
      // (only those accept() reads: an active rigid one's are not)
      const ConstraintState& r = rows[i];
      const bool gap = active_set.reads_gap(i), rate = active_set.reads_rate(i);
      const double Gq = gap || rate ? G_dot(i, x.q) : 0.;
      gaps[i] = gap ? Gq + r.z : 0.;
      rates[i] =
          rate ? r.G_t.dot(x.q) + c_v * (Gq - G_q_hat[i]) + G_v_hat[i] + r.z_t : 0.;
    }
    if (active_set.accept(gaps, x.lambda, t1, step_number + 1, rates))
      break;
    ++stats.active_set_iterations;
  }
  stats.active_set_changes += active_set.changes_in_step();
  x.active = active_set.active();
  clamp_compliant_forces(system, x.lambda);

  // a, v, a_c from the Newmark relations (with q before the position
  // projection: mu corrects positions only, like the GGL multiplier of (38)).
  // In one pass, each entry as deal.II's add(), *=, equ() and += make it:
  // a_next = (q - q^) / (h^2 beta), v = v^ + h gamma a_next,
  // a = (1 - alpha_m) / (1 - alpha_f) a_next + w.
  dealii::Vector<double>& a_next = next_pseudo_acceleration;
  for (auto* y : {&a_next, &x.v, &x.a})
    y->reinit(n, true);
  newmark_update(
      n, f, 1. / (h * h * k.beta), h * k.gamma, (1. - k.alpha_m) / (1. - k.alpha_f),
      (touching ? q_newmark : x.q).begin(), current.q.begin(), current.v.begin(),
      a_n.begin(), current.a.begin(), a_next.begin(), x.v.begin(), x.a.begin());
  if (active_set.impact_in_step())
  {
    // The impact: velocities onto dg/dt = 0 with the complementary impulses
    // (positions hold already); the pseudo-acceleration restarts, a_{n+1} =
    // a_c,{n+1}.
    ImpactProjection::Result r =
        impacts.project(rows, active_set.holding_indices(), t1, x.lambda, h, x.q, x.v);
    x.impulse.swap(r.impulse);
    for (const unsigned int i : r.separated)
      x.active[i] = false;
    // Restart from the acceleration of the impact's end state with every
    // holding constraint held; its forces are not reported (x.lambda stays
    // the step's), the next step's active set decides on releases.
    std::vector<unsigned int> holding;
    for (const unsigned int i : active_set.holding_indices())
      if (x.active[i])
        holding.push_back(i);
    impacts.restart_acceleration(at_next.at(t1), holding, t1, x.q, x.v, x.lambda, x.a);
    a_next = x.a;
  }
  else
    project(
        rows, t1,
        [&](const unsigned int i)
        {
          // A fixed row has no G_t: its G_t q is +0, as velocity_residual() sums it.
          return S.moves[i] ? rows[i].velocity_residual(x.q, x.v)
                            : 0. + G_dot(i, x.v) + rows[i].z_t;
        },
        x.v, velocity_multipliers, "velocity projection");
  pseudo_acceleration.swap(a_next);
  spare = std::move(current);
  current = std::move(x);
  ++step_number;
  ++stats.steps;
}

void GeneralizedAlphaIntegrator::solve_position_level(
    const std::vector<ConstraintState>& rows, std::vector<double>& lambda)
{
  // Unknowns: the multipliers of the active rigid constraints (rows g = 0)
  // and the forces of the engaged compliant ones (rows: their law divided by
  // k, lambda/k + g + d dg/dt = 0 at t_{n+1}), i.e.
  // (G S^-1 G^T + C) lambda = -(g0 + d r0): implicit in the force, S
  // untouched. The fixed constraints form a sparse block, the moving ones
  // border it.
  std::fill(keep.begin(), keep.end(), false);
  Bordered& b = bordered;
  std::vector<unsigned int>& moving_in = b.moving_in;
  moving_in.clear();
  const auto select = [&](const unsigned int i)
  {
    if (S.moves[i])
      moving_in.push_back(i);
    else
      keep[S.position[i]] = true;
  };
  for (const unsigned int i : active_set.force_indices()) // touching: no lambda
    select(i);
  for (const unsigned int i : active_set.engaged_indices())
    select(i);
  fixed_S.select(keep);

  const unsigned int mF = S.fixed.size(), p = moving_in.size();
  dealii::Vector<double>&x = b.x, &y = b.y;
  std::vector<dealii::Vector<double>>&Bc = b.Bc, &Cr = b.Cr;
  dealii::FullMatrix<double>& D = b.D;
  b.reinit(mF, p);
  for (unsigned int k = 0; k < mF; ++k)
    if (keep[k])
    {
      const unsigned int i = S.fixed[k];
      const double d = ratio[i];
      x(k) = -(base_gap[i] + d * base_rate[i]) / (1. + d * c_v);
    }
  for (unsigned int c = 0; c < p; ++c)
  {
    const unsigned int i = moving_in[c];
    const LocalColumns& X = S.S_columns[S.position[i]];
    const double d = ratio[i];
    // Fixed row k, column c: G_k S^-1 G_c^T. Row c, fixed column k:
    // (1 + d c_v) G_c S^-1 G_k^T + d G_t,c S^-1 G_k^T (S symmetric). Both
    // +0, as reinit() left them, where the columns do not reach row k.
    fixed_at_row.rows_in(X.reach(), reached, seen);
    for (const unsigned int k : reached)
      if (keep[k])
      {
        const std::array<double, InterleavedColumns::width> GX =
            X.dots(rows[S.fixed[k]].G); // both columns in one pass
        Bc[c](k) = GX[lambda_column];
        Cr[c](k) = (1. + d * c_v) * Bc[c](k) + d * GX[rate_column];
      }
    y(c) = -(base_gap[i] + d * base_rate[i]);
    for (unsigned int r = 0; r < p; ++r)
    {
      const unsigned int j = moving_in[r];
      const double d_r = ratio[j];
      D(r, c) = (1. + d_r * c_v) * X.dot(rows[j].G, lambda_column) +
                d_r * X.dot(rows[j].G_t, lambda_column);
    }
    if (system.constraints[i]->is_compliant())
      D(c, c) += 1. / system.constraints[i]->compliance().stiffness;
  }
  solve_bordered([&](const auto& xs) { fixed_S.solve(xs); }, Bc, Cr, D, x, y, b.rhs,
                 b.batch, current.t + h, "generalized-alpha step");
  std::fill(lambda.begin(), lambda.end(), 0.);
  for (unsigned int k = 0; k < mF; ++k)
    lambda[S.fixed[k]] = factors[k] = keep[k] ? x(k) : 0.;
  for (unsigned int c = 0; c < p; ++c)
    lambda[moving_in[c]] = y(c);
}

void GeneralizedAlphaIntegrator::assemble_positions(const std::vector<double>& lambda,
                                                    dealii::Vector<double>& q)
{
  q.swap(S.base); // q0, its vector taken (advance() solves for it again if needed)
  fixed_S.add_columns(factors, q);
  for (unsigned int c = 0; c < S.moving.size(); ++c)
    if (lambda[S.moving[c]] != 0.)
      S.S_columns[c].add_combination({{lambda[S.moving[c]], 0., 0., 0.}}, q);
}

template <typename Residual>
void GeneralizedAlphaIntegrator::project(const std::vector<ConstraintState>& rows,
                                         const double t1, Residual residual,
                                         dealii::Vector<double>& target,
                                         std::vector<double>& multipliers,
                                         const char* what)
{
  // (G M^-1 G^T) y = -residual on the rigid constraints that hold, the fixed
  // ones a sparse block, the moving ones its border; target += M^-1 G^T y.
  multipliers.assign(system.n_constraints(), 0.);
  const auto& A = active_set.active_indices();
  if (A.empty())
    return;
  std::fill(keep.begin(), keep.end(), false);
  Bordered& b = bordered;
  std::vector<unsigned int>& moving_in = b.moving_in;
  moving_in.clear();
  for (const unsigned int i : A)
    if (S.moves[i])
      moving_in.push_back(i);
    else
      keep[S.position[i]] = true;
  fixed_M.select(keep);
  const unsigned int mF = S.fixed.size(), p = moving_in.size();
  dealii::Vector<double>&x = b.x, &y = b.y;
  std::vector<dealii::Vector<double>>&Bc = b.Bc, &Cr = b.Cr;
  dealii::FullMatrix<double>& D = b.D;
  b.reinit(mF, p);
  for (unsigned int k = 0; k < mF; ++k)
    if (keep[k])
      x(k) = -residual(S.fixed[k]);
  for (unsigned int c = 0; c < p; ++c)
  {
    const LocalColumns& U = S.M_columns[S.position[moving_in[c]]];
    fixed_at_row.rows_in(U.reach(), reached, seen);
    for (const unsigned int k : reached)
      if (keep[k]) // the others +0, as reinit() left them
        Bc[c](k) = U.dot(rows[S.fixed[k]].G, 0);
    for (unsigned int r = 0; r < p; ++r)
      D(r, c) = U.dot(rows[moving_in[r]].G, 0);
    y(c) = -residual(moving_in[c]);
  }
  for (unsigned int c = 0; c < p; ++c)
    Cr[c] = Bc[c];
  solve_bordered([&](const auto& xs) { fixed_M.solve(xs); }, Bc, Cr, D, x, y, b.rhs,
                 b.batch, t1, what);
  std::vector<double>& fixed_part = b.fixed_part;
  fixed_part.assign(mF, 0.);
  for (unsigned int k = 0; k < mF; ++k)
    if (keep[k])
      multipliers[S.fixed[k]] = fixed_part[k] = x(k);
  fixed_M.add_columns(fixed_part, target);
  for (unsigned int c = 0; c < p; ++c)
  {
    multipliers[moving_in[c]] = y(c);
    S.M_columns[S.position[moving_in[c]]].add_combination({{y(c), 0., 0., 0.}}, target);
  }
}

void GeneralizedAlphaIntegrator::Bordered::reinit(const unsigned int mF,
                                                  const unsigned int p)
{
  x.reinit(mF);
  y.reinit(p);
  for (auto* columns : {&Bc, &Cr})
  {
    columns->resize(p);
    for (dealii::Vector<double>& column : *columns)
      column.reinit(mF);
  }
  D.reinit(p, p);
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
