#include <pantocat/time/dynamic_state_serialization.h>
#include <pantocat/time/generalized_alpha_integrator.h>

namespace pantocat
{
namespace
{
/**
 * S = K + c_v D + c_q M with, for each compliant constraint of law
 * lambda/k + g + d dg/dt = 0, the compliance 1 / (k (1 + d c_v)) and the
 * rate weight d / (1 + d c_v) of its row (the class documentation).
 */
ConstrainedOperator::Definition iteration_matrix(const SemiDiscreteSystem& system,
                                                 const double c_q, const double c_v,
                                                 const LinearSolverType solver)
{
  ConstrainedOperator::Definition S;
  S.mass = c_q;
  S.damping = c_v;
  S.stiffness = 1.;
  S.what = "generalized-alpha iteration matrix K + c_v D + c_q M";
  S.solver = solver;
  for (const auto& c : system.constraints)
  {
    const double d = c->is_compliant() ? damping_ratio(*c) : 0.;
    S.compliance.push_back(
        c->is_compliant() ? 1. / (c->compliance().stiffness * (1. + d * c_v)) : 0.);
    S.rate_weight.push_back(d / (1. + d * c_v));
  }
  return S;
}

/// The predictors of one unknown from its q_n, v_n, a_n and a_c,n: formed
/// where they are used, in the passes of predict() and newmark_update(),
/// instead of being stored (each pass over the state costs as much as the
/// arithmetic of a step on long sections).
struct Predictor
{
  double h, hq, hv, wm, wf;
  /// q^ = q_n + h v_n + h^2 (1/2 - beta) a_n.
  double q_hat(const double q, const double v, const double a) const
  {
    return q + h * v + hq * a;
  }
  /// v^ = v_n + h (1 - gamma) a_n.
  double v_hat(const double v, const double a) const { return v + hv * a; }
  /// w = (alpha_m a_n - alpha_f a_c,n) / (1 - alpha_f).
  double w(const double a, const double a_c) const { return wm * a + wf * a_c; }
};

Predictor predictor_of(const GeneralizedAlphaIntegrator::Coefficients& k, const double h)
{
  return {h, h * h * (0.5 - k.beta), h * (1. - k.gamma), k.alpha_m / (1. - k.alpha_f),
          -k.alpha_f / (1. - k.alpha_f)};
}

/**
 * predict()'s pass: mass_part = c_q q^ - w, damping_part = c_v q^ - v^ for
 * the unknowns [0, n) (restrict pointers and an AVX2 clone so that the pass
 * vectorises: it costs as much as the step's banded solve otherwise).
 */
__attribute__((target_clones("avx2", "default"))) void
right_hand_side_parts(const unsigned int n, const Predictor P, const double c_q,
                      const double c_v, const double* __restrict q,
                      const double* __restrict v, const double* __restrict a,
                      const double* __restrict a_c, double* __restrict mass_part,
                      double* __restrict damping_part)
{
  for (unsigned int i = 0; i < n; ++i)
  {
    const double q_hat = P.q_hat(q[i], v[i], a[i]);
    mass_part[i] = c_q * q_hat - P.w(a[i], a_c[i]);
    damping_part[i] = c_v * q_hat - P.v_hat(v[i], a[i]);
  }
}

/**
 * newmark_update()'s pass: a_next = (q - q^) fa, v = v^ + fv a_next,
 * a = fw a_next + w for the unknowns [0, n) (as right_hand_side_parts()).
 */
__attribute__((target_clones("avx2", "default"))) void
newmark_pass(const unsigned int n, const Predictor P, const double fa, const double fv,
             const double fw, const double* __restrict q, const double* __restrict q_n,
             const double* __restrict v_n, const double* __restrict a_n,
             const double* __restrict a_c, double* __restrict a_next,
             double* __restrict v, double* __restrict a)
{
  for (unsigned int i = 0; i < n; ++i)
  {
    a_next[i] = (q[i] - P.q_hat(q_n[i], v_n[i], a_n[i])) * fa;
    v[i] = P.v_hat(v_n[i], a_n[i]) + fv * a_next[i];
    a[i] = fw * a_next[i] + P.w(a_n[i], a_c[i]);
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
    const unsigned int max_iterations, const LinearSolverType linear_solver,
    const LinearAlgebra algebra)
    : TimeIntegrator(system), h(time_step), k(rho_infinity),
      c_q((1. - k.alpha_m) / ((1. - k.alpha_f) * k.beta * h * h)),
      c_v(k.gamma / (k.beta * h)),
      S(make_constrained_operator(
          system, iteration_matrix(system, c_q, c_v, linear_solver), algebra)),
      M(make_mass_operator(system, algebra, linear_solver)), at_next(system),
      active_set(system, max_iterations, ActiveSetIteration::ClosingConstraint::touching),
      impacts(system, *M)
{
  for (const auto& c : system.constraints)
    ratio.push_back(c->is_compliant() ? damping_ratio(*c) : 0.);
}

void GeneralizedAlphaIntegrator::initialize(const DynamicState& initial)
{
  current = initial;
  current.impulse.clear();
  pseudo_acceleration = initial.a; // a_0 = a_c,0 (Arnold and Bruels)
  step_number = 0;
}

void GeneralizedAlphaIntegrator::predict()
{
  // h = c_q q^ - w and r = c_v q^ - v^ of the step's right-hand side
  // f + M h + D r, in one pass.
  const unsigned int n = system.n_dofs();
  mass_part.reinit(n, true);
  damping_part.reinit(n, true);
  right_hand_side_parts(n, predictor_of(k, h), c_q, c_v, current.q.begin(),
                        current.v.begin(), pseudo_acceleration.begin(), current.a.begin(),
                        mass_part.begin(), damping_part.begin());
}

double GeneralizedAlphaIntegrator::newmark_rate(const unsigned int i,
                                                const ConstraintState& row,
                                                const dealii::Vector<double>& q) const
{
  // dg/dt = G_t q + G v + z_t with v = v^ + c_v (q - q^).
  return row.G_t.dot(q) + c_v * (row.G.dot(q) - G_q_hat[i]) + G_v_hat[i] + row.z_t;
}

void GeneralizedAlphaIntegrator::solve_without_forces(
    const std::vector<ConstraintState>& rows, const double t1)
{
  // S q0 = f(t_{n+1}) + M (c_q q^ - w) + D (c_v q^ - v^).
  S->solve_history(t1, mass_part, damping_part, q0);
  q0_current = true;
  const Predictor P = predictor_of(k, h);
  const unsigned int m = system.n_constraints();
  base_gap.assign(m, 0.);
  base_rate.assign(m, 0.);
  G_q_hat.assign(m, 0.);
  G_v_hat.assign(m, 0.);
  for (unsigned int i = 0; i < m; ++i)
  {
    base_gap[i] = rows[i].position_residual(q0);
    if (!system.constraints[i]->is_compliant())
      continue;
    const SparseRow& G = rows[i].G;
    for (std::size_t e = 0; e < G.index.size(); ++e)
    {
      const unsigned int j = G.index[e];
      G_q_hat[i] +=
          G.value[e] * P.q_hat(current.q[j], current.v[j], pseudo_acceleration[j]);
      G_v_hat[i] += G.value[e] * P.v_hat(current.v[j], pseudo_acceleration[j]);
    }
    base_rate[i] = newmark_rate(i, rows[i], q0);
  }
}

bool GeneralizedAlphaIntegrator::trial(const std::vector<ConstraintState>& rows,
                                       const double t1, DynamicState& x)
{
  // The position level: G S^-1 G^T lambda = -g0 on the rigid constraints
  // that carry a force; -(g0 + d r0) / (1 + d c_v) for the engaged compliant
  // ones (with their C and e in S's multiplier system).
  std::vector<unsigned int> set = active_set.force_indices();
  const std::vector<unsigned int>& engaged = active_set.engaged_indices();
  set.insert(set.end(), engaged.begin(), engaged.end());
  x.lambda.assign(system.n_constraints(), 0.);
  for (const unsigned int i : set)
    x.lambda[i] = -(base_gap[i] + ratio[i] * base_rate[i]) / (1. + ratio[i] * c_v);
  S->solve_multipliers(set, x.lambda, "generalized-alpha step");
  // x.q takes q0's vector (no copy of the state); a repeated trial solves
  // for q0 again, the same bits.
  if (!q0_current)
    S->solve_history(t1, mass_part, damping_part, q0);
  x.q.swap(q0);
  q0_current = false;
  S->add_columns(x.lambda, x.q);
  touching = active_set.force_indices().size() != active_set.active_indices().size();
  if (touching)
  {
    // Touching constraints hold by the position projection alone (the
    // Newmark relations take q before it).
    q_newmark = x.q;
    M->project(
        active_set.active_indices(),
        [&](const unsigned int i) { return rows[i].position_residual(x.q); }, x.q,
        position_multipliers, "position projection");
  }
  const unsigned int m = system.n_constraints();
  gaps.assign(m, 0.);
  rates.assign(m, 0.);
  for (unsigned int i = 0; i < m; ++i)
  {
    if (active_set.reads_gap(i))
      gaps[i] = rows[i].position_residual(x.q);
    if (active_set.reads_rate(i))
      rates[i] = newmark_rate(i, rows[i], x.q);
  }
  return active_set.accept(gaps, x.lambda, t1, step_number + 1, rates);
}

void GeneralizedAlphaIntegrator::newmark_update(const dealii::Vector<double>& q,
                                                DynamicState& x)
{
  // a_{n+1} = (q - q^) / (h^2 beta), v = v^ + h gamma a_{n+1},
  // a_c = (1 - alpha_m) / (1 - alpha_f) a_{n+1} + w, in one pass.
  const unsigned int n = system.n_dofs();
  dealii::Vector<double>& a_next = next_pseudo_acceleration;
  for (auto* y : {&a_next, &x.v, &x.a})
    y->reinit(n, true);
  newmark_pass(n, predictor_of(k, h), 1. / (h * h * k.beta), h * k.gamma,
               (1. - k.alpha_m) / (1. - k.alpha_f), q.begin(), current.q.begin(),
               current.v.begin(), pseudo_acceleration.begin(), current.a.begin(),
               a_next.begin(), x.v.begin(), x.a.begin());
}

void GeneralizedAlphaIntegrator::project_velocities(
    const std::vector<ConstraintState>& rows, const double t1, DynamicState& x)
{
  if (!active_set.impact_in_step())
  {
    std::vector<double> eta;
    M->project(
        active_set.active_indices(),
        [&](const unsigned int i) { return rows[i].velocity_residual(x.q, x.v); }, x.v,
        eta, "velocity projection");
    return;
  }
  // The impact: velocities onto dg/dt = 0 with the complementary impulses
  // (positions hold already).
  ImpactProjection::Result r =
      impacts.project(rows, active_set.holding_indices(), t1, x.lambda, h, x.q, x.v);
  x.impulse.swap(r.impulse);
  for (const unsigned int i : r.separated)
    x.active[i] = false;
  // The impact changes the velocities only: a_{n+1} and a_c,{n+1} stay
  // those of the step, the smooth part of the motion (doc/impacts.md).
}

void GeneralizedAlphaIntegrator::advance()
{
  const double t1 = current.t + h;
  const std::vector<ConstraintState>& rows = at_next.at(t1, 1);
  S->set_rows(rows, t1);
  M->set_rows(rows, t1);
  predict();
  solve_without_forces(rows, t1);
  DynamicState x = std::move(spare); // its vectors' memory
  x.t = t1;
  x.impulse.clear();
  active_set.start(current.active);
  while (!trial(rows, t1, x))
    ++stats.active_set_iterations;
  stats.active_set_changes += active_set.changes_in_step();
  x.active = active_set.active();
  clamp_compliant_forces(system, x.lambda);
  // a, v, a_c from q before the position projection (mu corrects positions
  // only, like the GGL multiplier of (38)).
  newmark_update(touching ? q_newmark : x.q, x);
  project_velocities(rows, t1, x);
  pseudo_acceleration.swap(next_pseudo_acceleration);
  spare = std::move(current);
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
  e.create_with_linear_algebra = [](const SemiDiscreteSystem& system,
                                    const TimeIntegrationParameters& p,
                                    const LinearAlgebra algebra)
  {
    return std::make_unique<GeneralizedAlphaIntegrator>(
        system, p.time_step, p.rho_infinity, p.max_active_set_iterations, p.linear_solver,
        algebra);
  };
  e.create = [make = e.create_with_linear_algebra](const SemiDiscreteSystem& system,
                                                   const TimeIntegrationParameters& p)
  { return make(system, p, LinearAlgebra::fast); };
  return e;
}
} // namespace pantocat
