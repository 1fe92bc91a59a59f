#include <pantocat/base/input_error.h>
#include <pantocat/time/dynamic_state_serialization.h>
#include <pantocat/time/half_explicit_integrator.h>
#include <pantocat/constrained_fast/multiplier_system.h>
#include <pantocat/time/unconstrained_prediction.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <type_traits>

namespace pantocat
{

HalfExplicitIntegrator::HalfExplicitIntegrator(const SemiDiscreteSystem& system,
                                               const double time_step,
                                               const unsigned int max_iterations)
    : TimeIntegrator(system), dt(time_step), at_n(system), at_half(system),
      at_next(system), active_set(system, max_iterations), impacts(system, mass_inverse)
{
  const unsigned int n = system.n_dofs(), m = system.n_constraints();
  for (auto* x : {&q, &v, &v_prev, &a, &q_new, &v_new})
    x->reinit(n);
  lambda.assign(m, 0.);
  gaps.assign(m, 0.);
  position.assign(m, -1);
  for (unsigned int i = 0; i < m; ++i)
  {
    const Constraint& c = *system.constraints[i];
    if (c.is_compliant())
      compliant.push_back(i);
    else if (c.depends_on_time())
    {
      position[i] = moving.size();
      moving.push_back(i);
    }
    else
    {
      position[i] = fixed.size();
      fixed.push_back(i);
    }
  }
  columns.resize(moving.size());
  for (MovingColumns& c : columns)
    for (auto* x : {&c.Y, &c.P, &c.Q, &c.R, &c.U, &c.V})
      x->reinit(n);
  mass_inverse.initialize(system.mass, system.mass_is_diagonal, "mass matrix M");
  factorize();
  // Diagonal storage of K and D/2.
  static_cast<ForceDiagonals&>(forces) = ForceDiagonals(system.stiffness, system.damping);
  const int b = forces.bandwidth;
  forces.symmetric_stiffness = true;
  for (int o = 1; o <= b; ++o)
    for (int i = 0; i + o < static_cast<int>(n); ++i)
      forces.symmetric_stiffness =
          forces.symmetric_stiffness &&
          forces.stiffness[b + o][i] == forces.stiffness[b - o][i + o];
  std::vector<bool> coupled(n, false);
  for (unsigned int i = 0; i < n; ++i)
    for (auto d = system.damping.begin(i); d != system.damping.end(i); ++d)
      if (d->column() != i && d->value() != 0.)
      {
        forces.listed_damping.push_back({i, d->column(), 0.5 * d->value()});
        coupled[i] = true;
      }
  // Is every damped row a coupled one? Then the diagonal goes into the list too.
  forces.damped_rows_coupled = true;
  for (unsigned int i = 0; i < n; ++i)
    if (forces.half_damping[b][i] != 0. && !coupled[i])
      forces.damped_rows_coupled = false;
  if (forces.damped_rows_coupled)
    for (unsigned int i = 0; i < n; ++i)
      if (forces.half_damping[b][i] != 0.)
        forces.listed_damping.push_back({i, i, forces.half_damping[b][i]});
  force_sweep.initialize(n, b, forces.stiffness_offsets, forces.stiffness,
                         forces.damping_offsets, forces.half_damping);
  for (const unsigned int i : fixed)
  {
    fixed_rows.push_back(at_n.states()[i].G);
    fixed_rows.offset.push_back(at_n.states()[i].z);
  }
  is_moving.assign(m, false);
  for (const unsigned int i : moving)
    is_moving[i] = true;
  fixed_by_unknown.build(fixed_rows, n); // find_fixed_near()
  near_mark.assign(fixed.size(), false);
  corrected_slot.assign(fixed.size(), -1);
  take_disjoint_fixed_constraints();
}

void HalfExplicitIntegrator::take_disjoint_fixed_constraints()
{
  disjoint.initialize(fixed_rows, fixed_rows.offset, fixed, smoothed_mass_inverse,
                      mass_inverse, system.n_dofs());
  project_now.assign(fixed.size(), true);
  // The rows whose a changes after the sweep with a constant pattern: the
  // coupled rows, and the rows of the fixed constraints (their columns
  // (M + dt/2 D)^-1 G^T live there and on the coupled rows when it is
  // diagonal), unless DisjointFixedConstraints predicts those itself.
  constant_refresh_rows.clear();
  for (const auto& entry : forces.listed_damping)
    constant_refresh_rows.push_back(entry.row);
  if (!disjoint.used())
    for (const unsigned int j : fixed_rows.index)
      constant_refresh_rows.push_back(j);
  std::sort(constant_refresh_rows.begin(), constant_refresh_rows.end());
  constant_refresh_rows.erase(
      std::unique(constant_refresh_rows.begin(), constant_refresh_rows.end()),
      constant_refresh_rows.end());
}

namespace
{
/**
 * out = scale * (f - K q - D/2 (v_prev + v)) in one sweep for a symmetric K
 * of half bandwidth B and a diagonal D (the FDM and lumped-pantograph case):
 * K(i, i+o) = K(i+o, i) is read from the upper diagonals only (fewer streams
 * through the cache), the offsets are compile-time constants (the row loop
 * vectorises), and the diagonal scaling of (M + dt/2 D)^-1 is fused in.
 *
 * With @p predict, the same sweep also writes the unconstrained step of (40),
 * v* = v_prev + 2 dt a and q* = q + dt (v + v*)/2, into @p v_new and
 * @p q_new: one pass over the unknowns per step instead of two. Rows whose a
 * changes afterwards (constraint forces, coupled rows) are predicted again
 * from their final a (HalfExplicitIntegrator::refresh_prediction()).
 */
/// A uniform run's coefficients as values (local scalars for the compiler).
struct RunCoefficients
{
  double f, k0, d0, scale, u1, l1, u2, l2, u3, l3;
};

inline RunCoefficients coefficients_of(const UniformForceRun& run)
{
  return {run.f,        run.k0,       run.d0,       run.scale,    run.upper[0],
          run.lower[0], run.upper[1], run.lower[1], run.upper[2], run.lower[2]};
}

/// The acceleration of row @p i of a uniform run with coefficients @p c.
template <int B, bool damped, bool symmetric>
inline double run_acceleration(const RunCoefficients& c, const int i,
                               const double* __restrict q, const double* __restrict vp,
                               const double* __restrict v)
{
  double s = c.f - c.k0 * q[i];
  if constexpr (damped)
    s -= c.d0 * (vp[i] + v[i]);
  if constexpr (symmetric) // K(i, i+o) = K(i, i-o): one product per pair
  {
    s -= c.u1 * (q[i - 1] + q[i + 1]);
    if constexpr (B >= 2)
      s -= c.u2 * (q[i - 2] + q[i + 2]);
    if constexpr (B >= 3)
      s -= c.u3 * (q[i - 3] + q[i + 3]);
  }
  else
  {
    s -= c.u1 * q[i + 1];
    s -= c.l1 * q[i - 1];
    if constexpr (B >= 2)
    {
      s -= c.u2 * q[i + 2];
      s -= c.l2 * q[i - 2];
    }
    if constexpr (B >= 3)
    {
      s -= c.u3 * q[i + 3];
      s -= c.l3 * q[i - 3];
    }
  }
  return s * c.scale;
}

/// The acceleration (and prediction) of one exception @p x of a uniform run.
template <int B, bool damped, bool predict, bool symmetric>
inline void exception_force(const RunCoefficients& c, const ForceException& x,
                            const double* __restrict q, const double* __restrict vp,
                            const double* __restrict v, double* __restrict out,
                            const double two_dt, const double half_dt,
                            double* __restrict q_new, double* __restrict v_new)
{
  RunCoefficients own = c;
  own.f = x.f;
  own.d0 = x.d0;
  own.scale = x.scale;
  const double acceleration =
      run_acceleration<B, damped, symmetric>(own, x.row, q, vp, v);
  out[x.row] = acceleration;
  if constexpr (predict)
    if (x.predict)
      predict_unconstrained(x.row, acceleration, two_dt, half_dt, q, v, vp, q_new, v_new);
}

/**
 * banded_forces() on the rows of one uniform run: its coefficients as local
 * scalars, every pointer restrict, so that the loop vectorises. The
 * operations and their order are those of banded_forces()'s rows; with
 * @p symmetric (K(i, i+o) = K(i, i-o) in the run: the wires' interiors) each
 * pair of neighbours takes one product, k_o (q_{i-o} + q_{i+o}), as the
 * single-sweep kernel of bench/ does. Then the run's exceptions (rows with
 * their own f, D/2 and scaling) are done again with their values. Compiled
 * for AVX2 beside the baseline, chosen when the program starts: four rows per
 * instruction instead of two, the same operations (no fused multiply-add), so
 * the same bits.
 */
template <int B, bool damped, bool predict, bool symmetric>
__attribute__((target_clones("avx2", "default"))) void
uniform_run_forces(const UniformForceRun& run, const ForceException* exceptions,
                   const double* __restrict q, const double* __restrict vp,
                   const double* __restrict v, double* __restrict out, const double dt,
                   double* __restrict q_new, double* __restrict v_new)
{
  const RunCoefficients c = coefficients_of(run);
  const double two_dt = 2. * dt, half_dt = 0.5 * dt;
  // Blocks of rows, each followed by its exceptions (in row order) while
  // the block's rows are in the first-level cache.
  constexpr int block = 256;
  int e = run.first_exception;
  for (int first = run.first; first < run.last; first += block)
  {
    const int last = std::min(run.last, first + block);
    for (int i = first; i < last; ++i)
    {
      const double acceleration = run_acceleration<B, damped, symmetric>(c, i, q, vp, v);
      out[i] = acceleration;
      if constexpr (predict)
        predict_unconstrained(i, acceleration, two_dt, half_dt, q, v, vp, q_new, v_new);
    }
    for (; e < run.last_exception && exceptions[e].row < last; ++e)
      exception_force<B, damped, predict, symmetric>(c, exceptions[e], q, vp, v, out,
                                                     two_dt, half_dt, q_new, v_new);
  }
}

template <int B, bool damped, bool predict>
void banded_forces(const int n, const double* __restrict f,
                   const std::vector<std::vector<double>>& K, const double* __restrict d0,
                   const double* __restrict scale, const double* __restrict q,
                   const double* __restrict vp, const double* __restrict v,
                   double* __restrict out, const double dt, double* __restrict q_new,
                   double* __restrict v_new,
                   const std::vector<UniformForceRun>* runs = nullptr,
                   const ForceException* exceptions = nullptr)
{
  const double* k[B + 1]; // k[o][i] = K(i, i + o)
  for (int o = 0; o <= B; ++o)
    k[o] = K[B + o].data();
  const auto finish = [&](const int i, const double acceleration)
  {
    out[i] = acceleration;
    if constexpr (predict)
      predict_unconstrained(i, acceleration, 2. * dt, 0.5 * dt, q, v, vp, q_new, v_new);
  };
  auto row = [&](const int i, const bool interior)
  {
    double s = f[i] - k[0][i] * q[i];
    if constexpr (damped)
      s -= d0[i] * (vp[i] + v[i]);
    for (int o = 1; o <= B; ++o)
    {
      if (interior || i + o < n)
        s -= k[o][i] * q[i + o];
      if (interior || i - o >= 0)
        s -= k[o][i - o] * q[i - o];
    }
    finish(i, s * scale[i]);
  };
  if (runs)
  {
    // The same operations in the same order, with the coefficients of a run
    // of equal rows held in registers: three streams read instead of eight.
    for (const UniformForceRun& r : *runs)
    {
      if (!r.uniform)
      {
        for (int i = r.first; i < r.last; ++i)
          row(i, i >= B && i < n - B);
        continue;
      }
      // A run's own reach: a string's rows skip the beam's zero diagonals
      // (subtracting 0 q_j changes nothing for finite q).
      const auto sweep = [&](auto reach)
      {
        constexpr int R = decltype(reach)::value;
        if (r.symmetric)
          uniform_run_forces<R, damped, predict, true>(r, exceptions, q, vp, v, out, dt,
                                                       q_new, v_new);
        else
          uniform_run_forces<R, damped, predict, false>(r, exceptions, q, vp, v, out, dt,
                                                        q_new, v_new);
      };
      if (B >= 3 && r.reach == 3)
        sweep(std::integral_constant<int, 3>());
      else if (B >= 2 && r.reach == 2)
        sweep(std::integral_constant<int, 2>());
      else
        sweep(std::integral_constant<int, 1>());
    }
    return;
  }
  for (int i = 0; i < std::min(B, n); ++i)
    row(i, false);
  for (int i = B; i < n - B; ++i)
    row(i, true);
  for (int i = std::max(B, n - B); i < n; ++i)
    row(i, false);
}
/**
 * predict_unconstrained() on the unknowns 0 .. n-1 in one loop with a signed
 * index, so that it runs in four-double vectors (AVX2 clone).
 */
__attribute__((target_clones("avx2", "default"))) void
predict_all(const int n, const double* __restrict a, const double two_dt,
            const double half_dt, const double* __restrict q, const double* __restrict v,
            const double* __restrict vp, double* __restrict q_new,
            double* __restrict v_new)
{
  for (int i = 0; i < n; ++i)
    predict_unconstrained(i, a[i], two_dt, half_dt, q, v, vp, q_new, v_new);
}
} // namespace

const double* HalfExplicitIntegrator::load_at_time_n()
{
  if (!system.has_time_dependent_load())
    return system.load.begin();
  system.load_at(t, load_now);
  return load_now.begin();
}

void HalfExplicitIntegrator::compute_forces()
{
  const int n = q.size(), b = forces.bandwidth;
  const double* __restrict qq = q.begin();
  const double* __restrict vv = v.begin();
  const double* __restrict vp = previous->begin();
  double* __restrict out = a.begin();
  // Damping is diagonal but for a few rows (a lumped pantograph's dampers):
  // the fused sweep with the diagonal, then those entries.
  const dealii::Vector<double>* scaling = smoothed_mass_inverse.row_scaling();
  if (forces.listed_damping.size() <= 16 && b >= 1 && b <= 3 &&
      forces.symmetric_stiffness && scaling)
  {
    const double* d0 = forces.half_damping[b].data();
    const double* f = load_at_time_n();
    const double* scale = scaling->begin();
    double* qn = q_new.begin();
    double* vn = v_new.begin();
    if (!uniform_runs_built)
      build_uniform_runs(scale);
    const std::vector<UniformForceRun>* runs =
        uniform_runs.empty() || system.has_time_dependent_load() ? nullptr
                                                                 : &uniform_runs;
    const auto sweep = [&](auto damped)
    {
      constexpr bool D = decltype(damped)::value;
      if (b == 1)
        banded_forces<1, D, true>(n, f, forces.stiffness, d0, scale, qq, vp, vv, out, dt,
                                  qn, vn, runs, force_exceptions.data());
      else if (b == 2)
        banded_forces<2, D, true>(n, f, forces.stiffness, d0, scale, qq, vp, vv, out, dt,
                                  qn, vn, runs, force_exceptions.data());
      else
        banded_forces<3, D, true>(n, f, forces.stiffness, d0, scale, qq, vp, vv, out, dt,
                                  qn, vn, runs, force_exceptions.data());
    };
    predicted = true;
    if (forces.damped_rows_coupled)
      sweep(std::false_type{});
    else
      sweep(std::true_type{});
    // The coupled rows (unscaled by row_scaling) get their dampers, then their block.
    for (const auto& [i, j, d] : forces.listed_damping)
      out[i] -= d * (vp[j] + vv[j]);
    add_compliant_loads(out, scale);
    smoothed_mass_inverse.apply_coupled_rows(a);
    return;
  }
  predicted = false;
  if (free_acceleration_ready)
  {
    if (free_acceleration_taken)
      solve_free_acceleration();
    a.swap(free_acceleration);
    free_acceleration_taken = true;
    return;
  }
  unscaled_forces(out);
  smoothed_mass_inverse.apply(a);
}

void HalfExplicitIntegrator::solve_free_acceleration()
{
  free_acceleration.reinit(system.n_dofs(), true);
  unscaled_forces(free_acceleration.begin());
  smoothed_mass_inverse.factorised()->solve(free_acceleration);
}

void HalfExplicitIntegrator::unscaled_forces(double* out)
{
  const double* __restrict qq = q.begin();
  const double* __restrict vv = v.begin();
  const double* __restrict vp = previous->begin();
  const double* f = load_at_time_n();
  force_sweep.apply(f, qq, vp, vv, out);
  add_compliant_loads(out, nullptr);
}

void HalfExplicitIntegrator::factorize()
{
  // (M + dt/2 D) of (39) with (41); diagonal when M and D are.
  dealii::SparseMatrix<double> smoothed(*system.sparsity);
  smoothed.copy_from(system.mass);
  smoothed.add(0.5 * dt, system.damping);
  bool diagonal = system.mass_is_diagonal;
  for (unsigned int i = 0; diagonal && i < system.n_dofs(); ++i)
    for (auto it = system.damping.begin(i); diagonal && it != system.damping.end(i); ++it)
      diagonal = it->column() == i || it->value() == 0.;
  smoothed_mass_inverse.initialize(smoothed, diagonal, "matrix M + dt/2 D");

  // The Schur complements of the rigid constraints with constant rows, once.
  std::vector<const SparseRow*> rows;
  for (const unsigned int i : fixed)
    rows.push_back(&at_n.states()[i].G);
  fixed_smoothed.initialize(rows, smoothed_mass_inverse, system.n_dofs(),
                            "matrix G (M + dt/2 D)^-1 G^T of the fixed constraints");
  fixed_mass.initialize(rows, mass_inverse, system.n_dofs(),
                        "matrix G M^-1 G^T of the fixed constraints");
}

void HalfExplicitIntegrator::set_time_step(const double time_step)
{
  dt = time_step;
  uniform_runs_built = false; // the scaling of (M + dt/2 D)^-1 changes
  history_start = step_number;
  factorize();
  take_disjoint_fixed_constraints();
}

void HalfExplicitIntegrator::initialize(const DynamicState& initial)
{
  t = initial.t;
  q = initial.q;
  v = initial.v;
  a = initial.a;
  // v_{-1} = v_0 - dt a_0.
  v_prev = initial.v;
  v_prev.add(-dt, initial.a);
  previous = &v_prev;
  active_now = initial.active;
  reported = initial;
  reported.impulse.clear();
  pending_impulse.clear();
  step_number = 0;
  history_start = 0;
}

void HalfExplicitIntegrator::set_previous_velocity(const dealii::Vector<double>& vp)
{
  v_prev = vp;
  previous = &v_prev;
  history_start = step_number;
}

void HalfExplicitIntegrator::find_fixed_near(std::initializer_list<const SparseRow*> rows,
                                             const MassInverse& A, const bool local,
                                             const RowRanges& reach,
                                             std::vector<unsigned int>& near)
{
  near.clear();
  const auto visit = [&](const unsigned int j)
  {
    for (unsigned int e = fixed_by_unknown.start[j]; e < fixed_by_unknown.start[j + 1];
         ++e)
    {
      const unsigned int k = fixed_by_unknown.row[e];
      if (!near_mark[k])
      {
        near_mark[k] = true;
        near.push_back(k);
      }
    }
  };
  if (local) // the column is zero off its reach
  {
    for (const RowRange& r : reach)
      for (int j = r.first; j < r.last; ++j)
        visit(j);
  }
  else if (A.factorised())
  {
    for (unsigned int k = 0; k < fixed.size(); ++k)
      near.push_back(k);
    return;
  }
  else
  {
    for (const SparseRow* row : rows)
      for (const unsigned int j : row->index)
        visit(j);
    for (const unsigned int j : A.coupled())
      visit(j);
  }
  for (const unsigned int k : near)
    near_mark[k] = false;
}

void HalfExplicitIntegrator::compute_moving_columns()
{
  const auto& sn = at_n.states();
  const auto& sh = at_half.states();
  const auto& s1 = at_next.states();
  const SparseDirectSolver* W = smoothed_mass_inverse.factorised();
  const SparseDirectSolver* M = mass_inverse.factorised();
  for (unsigned int c = 0; c < moving.size(); ++c)
  {
    const unsigned int i = moving[c];
    MovingColumns& x = columns[c];
    // a* = W^-1 (forces) once, with the first moving constraint (see free_acceleration).
    dealii::Vector<double>* free_rhs = c == 0 && W ? &free_acceleration : nullptr;
    if (W && M) // factorised (FEM): every column on the rows it reaches
      compute_factorised_columns(*W, *M, sn[i], sh[i], s1[i], x, free_rhs);
    else
    {
      if (W)
      {
        // M diagonal, M + dt/2 D banded (the FDM with Rayleigh damping): a* on
        // all rows, Y on the rows it reaches.
        if (free_rhs)
          W->solve(*free_rhs);
        compute_local_column(*W, sn[i].G, x);
      }
      else
        smoothed_mass_inverse.apply_to_row(sn[i].G, x.Y);
      mass_inverse.apply_to_row(sn[i].G, x.P);
      mass_inverse.apply_to_row(sh[i].G_t, x.Q);
      mass_inverse.apply_to_row(sh[i].G, x.R);
      if (!fixed.empty())
      {
        mass_inverse.apply_to_row(s1[i].G, x.U);
        mass_inverse.apply_to_row(s1[i].G_t, x.V);
      }
    }
    if (fixed.empty())
      continue;
    find_fixed_near({&sn[i].G}, smoothed_mass_inverse, x.local_Y, x.reach_Y, x.near_Y);
    find_fixed_near({&sn[i].G, &sh[i].G_t, &sh[i].G, &s1[i].G, &s1[i].G_t}, mass_inverse,
                    x.local_M, x.reach_M, x.near_M);
  }
}

namespace
{
/// @p column = 0 on the rows @p reach.
void zero_on(const RowRanges& reach, dealii::Vector<double>& column)
{
  for (const RowRange& r : reach)
    std::fill(column.begin() + r.first, column.begin() + r.last, 0.);
}

/// @p column = column k of @p X on the rows X reaches (zero elsewhere already).
void copy_out(const LocalColumns& X, const unsigned int k, dealii::Vector<double>& column)
{
  for (const RowRange& r : X.reach())
    for (int i = r.first; i < r.last; ++i)
      column[i] = X(i, k);
}
} // namespace

void HalfExplicitIntegrator::compute_factorised_columns(
    const SparseDirectSolver& W, const SparseDirectSolver& M, const ConstraintState& sn,
    const ConstraintState& sh, const ConstraintState& s1, MovingColumns& x,
    dealii::Vector<double>* free_rhs)
{
  // a* = W^-1 (forces) on all rows; the columns on the rows they reach
  // (SparseDirectSolver::solve_local()), the previous step's reset there.
  if (free_rhs)
    W.solve(*free_rhs);
  compute_local_column(W, sn.G, x);
  for (auto* column : {&x.P, &x.Q, &x.R, &x.U, &x.V})
    zero_on(x.reach_M, *column);
  x.local_M = true;
  local_M.clear();
  local_M.add_row(0, sn.G, 1.);
  local_M.add_row(1, sh.G_t, 1.);
  local_M.add_row(2, sh.G, 1.);
  if (!fixed.empty())
    local_M.add_row(3, s1.G, 1.);
  local_M.solve(M);
  x.reach_M = local_M.reach();
  for (const auto& [k, column] : {std::pair{0u, &x.P}, std::pair{1u, &x.Q},
                                  std::pair{2u, &x.R}, std::pair{3u, &x.U}})
    copy_out(local_M, k, *column);
  if (fixed.empty())
    return;
  local_V.clear();
  local_V.add_row(0, s1.G_t, 1.);
  local_V.solve(M);
  copy_out(local_V, 0, x.V);
  x.reach_M = union_of(x.reach_M, local_V.reach());
}

void HalfExplicitIntegrator::compute_local_column(const SparseDirectSolver& W,
                                                  const SparseRow& G, MovingColumns& x)
{
  const unsigned int n = system.n_dofs();
  if (local_W.size() != n)
    for (LocalColumns* X : {&local_W, &local_M, &local_V})
      X->reinit(n);
  zero_on(x.reach_Y, x.Y);
  x.local_Y = true;
  local_W.clear();
  local_W.add_row(0, G, 1.);
  local_W.solve(W);
  copy_out(local_W, 0, x.Y);
  x.reach_Y = local_W.reach();
}

void HalfExplicitIntegrator::add_moving_column(const MassInverse& A, const SparseRow& row,
                                               const dealii::Vector<double>& column,
                                               const bool local, const RowRanges& reach,
                                               const double factor,
                                               dealii::Vector<double>& y)
{
  if (!local)
  {
    A.add_column(row, column, factor, y);
    return;
  }
  for (const RowRange& r : reach)
    for (int i = r.first; i < r.last; ++i)
      y[i] += factor * column[i];
}

void HalfExplicitIntegrator::reset_moving_columns()
{
  if (smoothed_mass_inverse.factorised() && mass_inverse.factorised())
    return; // compute_factorised_columns() resets the rows it reached
  const auto& sn = at_n.states();
  const auto& sh = at_half.states();
  const auto& s1 = at_next.states();
  for (unsigned int c = 0; c < moving.size(); ++c)
  {
    const unsigned int i = moving[c];
    MovingColumns& x = columns[c];
    if (!x.local_Y) // else compute_local_column() resets the rows it reached
      smoothed_mass_inverse.reset_column(sn[i].G, x.Y);
    mass_inverse.reset_column(sn[i].G, x.P);
    mass_inverse.reset_column(sh[i].G_t, x.Q);
    mass_inverse.reset_column(sh[i].G, x.R);
    if (fixed.empty())
      continue;
    mass_inverse.reset_column(s1[i].G, x.U);
    mass_inverse.reset_column(s1[i].G_t, x.V);
  }
}

const HalfExplicitIntegrator::ActiveSplit&
HalfExplicitIntegrator::split_of(const std::vector<unsigned int>& A)
{
  for (const ActiveSplit& s : split_cache)
    if (s.valid && s.indices == A)
      return s;
  ActiveSplit& s = split_cache[next_split_slot];
  next_split_slot = 1 - next_split_slot;
  s.valid = true;
  s.version = ++split_versions;
  s.indices = A;
  s.keep.assign(fixed.size(), false);
  s.moving.clear();
  for (const unsigned int i : A)
  {
    if (is_moving[i])
      s.moving.push_back(i);
    else
      s.keep[position[i]] = true;
  }
  return s;
}

void HalfExplicitIntegrator::split(const std::vector<unsigned int>& A,
                                   std::vector<bool>& keep_fixed,
                                   std::vector<unsigned int>& moving_in_A)
{
  const ActiveSplit& s = split_of(A);
  keep_fixed = s.keep;
  moving_in_A = s.moving;
  keep_version = s.version;
}

void HalfExplicitIntegrator::MultiplierWorkspace::prepare(const unsigned int n_fixed,
                                                          const unsigned int n_moving)
{
  // Sizes change only with the active set's shape: zero in place otherwise
  // (deal.II's reinit and vector assignment cost more than these few entries).
  const auto zero = [](dealii::Vector<double>& v, const unsigned int n)
  {
    if (v.size() != n)
      v.reinit(n);
    else
      std::fill(v.begin(), v.end(), 0.);
  };
  zero(x, n_fixed);
  zero(y, n_moving);
  B.resize(n_moving);
  C.resize(n_moving);
  for (unsigned int c = 0; c < n_moving; ++c)
  {
    zero(B[c], n_fixed);
    zero(C[c], n_fixed);
  }
  if (D.m() != n_moving || D.n() != n_moving)
    D.reinit(n_moving, n_moving);
  else
    D = 0.;
}

void HalfExplicitIntegrator::compute_compliant_forces()
{
  const auto& sn = at_n.states();
  for (const unsigned int i : compliant)
  {
    // Explicit in the force: g and dg/dt at t_n from q_n and the velocity of
    // the damping forces of (39), (41), v_{n-1/2} = (v_{n-1} + v_n)/2.
    const ConstraintState& s = sn[i];
    const double gap = s.position_residual(q);
    const double rate = s.G_t.dot(q) + 0.5 * (s.G.dot(*previous) + s.G.dot(v)) + s.z_t;
    const Constraint& c = *system.constraints[i];
    lambda[i] = c.compliant_force(gap, rate);
    const bool engaged = !c.is_unilateral() || lambda[i] > 0.;
    // Counted once: a repetition of step 1 in the same step finds it set.
    stats.active_set_changes += engaged != active_now[i];
    active_now[i] = engaged;
  }
}

void HalfExplicitIntegrator::add_compliant_loads(double* f, const double* scaling) const
{
  const auto& sn = at_n.states();
  for (const unsigned int i : compliant)
    if (lambda[i] != 0.)
    {
      const SparseRow& G = sn[i].G;
      for (std::size_t k = 0; k < G.size(); ++k)
      {
        const unsigned int j = G.index[k];
        f[j] += lambda[i] * G.value[k] * (scaling ? scaling[j] : 1.);
      }
    }
}

void HalfExplicitIntegrator::add_acceleration_multipliers(
    const std::vector<unsigned int>& A)
{
  split(A, keep, moving_active);
  force_keep = keep;
  if (disjoint.used())
  {
    add_disjoint_acceleration_multipliers();
    return;
  }
  fixed_smoothed.select(keep);
  const unsigned int mF = fixed.size(), p = moving_active.size();
  if (mF + p == 0)
    return;
  acceleration_workspace.prepare(mF, p);
  dealii::Vector<double>& x = acceleration_workspace.x;
  // The fixed ones: G_t, G_tt, z_tt are 0.
  for (unsigned int k = 0; k < mF; ++k)
    if (keep[k])
      x(k) = -fixed_rows.dot(k, a.begin());
  fill_acceleration_border(
      [&](const MovingColumns& X, const auto& visit)
      {
        for (const unsigned int k : X.near_Y) // the others meet Y in zeros
          if (keep[k])
            visit(k, k);
      });
  solve_bordered(
      [&](const std::vector<dealii::Vector<double>*>& xs)
      {
        for (dealii::Vector<double>* v : xs)
          fixed_smoothed.solve(*v);
      },
      acceleration_workspace.B, acceleration_workspace.C, acceleration_workspace.D, x,
      acceleration_workspace.y, acceleration_workspace.rhs, acceleration_workspace.batch,
      t, "acceleration level");
  // a += (M + dt/2 D)^-1 G^T lambda: the fixed rows' truncated columns.
  factors.assign(mF, 0.);
  for (unsigned int k = 0; k < mF; ++k)
    if (keep[k])
      factors[k] = lambda[fixed[k]] = x(k);
  fixed_smoothed.add_columns(factors, a);
  add_moving_acceleration_forces();
}

template <typename NearFixed>
void HalfExplicitIntegrator::fill_acceleration_border(const NearFixed& near_fixed_of)
{
  const auto& sn = at_n.states();
  const unsigned int p = moving_active.size();
  dealii::Vector<double>& y = acceleration_workspace.y;
  std::vector<dealii::Vector<double>>& B = acceleration_workspace.B;
  std::vector<dealii::Vector<double>>& C = acceleration_workspace.C;
  dealii::FullMatrix<double>& D = acceleration_workspace.D;
  // The moving constraints border the fixed ones: B = G_F Y_c, C = B^T
  // ((M + dt/2 D) is symmetric), D = G_c Y_c'; g^(II) = G a + 2 G_t v + G_tt
  // q + z_tt = 0 at t_n.
  for (unsigned int c = 0; c < p; ++c)
  {
    const ConstraintState& s = sn[moving_active[c]];
    y(c) = -(s.G.dot(a) + 2. * s.G_t.dot(v) + s.G_tt.dot(q) + s.z_tt);
    const MovingColumns& X = columns[position[moving_active[c]]];
    near_fixed_of(X, [&](const unsigned int slot, const unsigned int k)
                  { B[c](slot) = fixed_rows.dot(k, X.Y.begin()); });
    for (unsigned int r = 0; r < p; ++r)
      D(r, c) = sn[moving_active[r]].G.dot(X.Y);
  }
  for (unsigned int c = 0; c < p; ++c)
    C[c] = B[c];
}

void HalfExplicitIntegrator::add_moving_acceleration_forces()
{
  const auto& sn = at_n.states();
  const dealii::Vector<double>& y = acceleration_workspace.y;
  for (unsigned int c = 0; c < moving_active.size(); ++c)
  {
    const unsigned int i = moving_active[c];
    lambda[i] = y(c);
    const MovingColumns& X = columns[position[i]];
    add_moving_column(smoothed_mass_inverse, sn[i].G, X.Y, X.local_Y, X.reach_Y, y(c), a);
  }
}

void HalfExplicitIntegrator::gather_near_fixed(
    std::vector<unsigned int> MovingColumns::*near)
{
  near_fixed.clear();
  for (const unsigned int i : moving_active)
    for (const unsigned int k : columns[position[i]].*near)
      if (keep[k] && !near_mark[k])
      {
        near_mark[k] = true;
        near_fixed.push_back(k);
      }
  for (const unsigned int k : near_fixed)
    near_mark[k] = false;
}

void HalfExplicitIntegrator::add_disjoint_acceleration_multipliers()
{
  disjoint.select_acceleration(keep, keep_version);
  const unsigned int p = moving_active.size();
  if (p > 0)
  {
    // The moving constraints' multipliers first, bordered by the fixed ones
    // on their unknowns only (the others' rows meet Y in zeros); then their
    // forces go into a, and every fixed constraint's multiplier follows from
    // its own row of the final a (DisjointFixedConstraints).
    gather_near_fixed(&MovingColumns::near_Y);
    const unsigned int nL = near_fixed.size();
    acceleration_workspace.prepare(nL, p);
    dealii::Vector<double>& x = acceleration_workspace.x;
    for (unsigned int l = 0; l < nL; ++l)
      x(l) = -fixed_rows.dot(near_fixed[l], a.begin());
    fill_acceleration_border(
        [&](const MovingColumns&, const auto& visit)
        {
          for (unsigned int l = 0; l < nL; ++l)
            visit(l, near_fixed[l]);
        });
    solve_bordered(
        [&](const std::vector<dealii::Vector<double>*>& xs)
        {
          for (dealii::Vector<double>* v : xs)
            for (unsigned int l = 0; l < nL; ++l)
              (*v)(l) *= disjoint.smoothed_inverse(near_fixed[l]);
        },
        acceleration_workspace.B, acceleration_workspace.C, acceleration_workspace.D, x,
        acceleration_workspace.y, acceleration_workspace.rhs,
        acceleration_workspace.batch, t, "acceleration level");
    add_moving_acceleration_forces();
  }
  const DisjointFixedConstraints::Prediction prediction{
      q.begin(), v.begin(), previous->begin(), q_new.begin(), v_new.begin(), dt};
  projected_early = predicted && update_set;
  if (!projected_early)
  {
    disjoint.accelerate(a.begin(), lambda, predicted ? &prediction : nullptr);
    return;
  }
  // (40) of the fixed constraints that no moving one borders in the same
  // pass: their q*, v* are final once their own rows are predicted.
  const ActiveSplit& update_split = split_of(*update_set);
  disjoint.select_position(update_split.keep, update_split.version);
  deferred_fixed.clear();
  for (const unsigned int i : moving)
    for (const unsigned int k : columns[position[i]].near_M)
      if (project_now[k])
      {
        project_now[k] = false;
        deferred_fixed.push_back(k);
      }
  disjoint.accelerate(a.begin(), lambda, &prediction, &project_now, &gaps);
  for (const unsigned int k : deferred_fixed)
    project_now[k] = true;
}

void HalfExplicitIntegrator::compute_acceleration(const std::vector<unsigned int>& A,
                                                  const std::vector<unsigned int>* update)
{
  update_set = update;
  std::fill(lambda.begin(), lambda.end(), 0.);
  // The compliant forces first: they join f of (39), and the rigid
  // multipliers' g^(II) = 0 sees them.
  compute_compliant_forces();
  // (M + dt/2 D) a = f - K q_n - D (v_{n-1} + v_n)/2 + G_c^T lambda_c: the smoothing
  // (41).
  compute_forces();
  add_acceleration_multipliers(A);
  if (predicted)
    refresh_prediction();
}

void HalfExplicitIntegrator::build_uniform_runs(const double* scale)
{
  uniform_runs.clear();
  force_exceptions.clear();
  uniform_runs_built = true;
  if (system.has_time_dependent_load())
    return;
  const int n = q.size(), b = forces.bandwidth;
  const bool damped = !forces.damped_rows_coupled;
  const auto coefficients = [&](const int i)
  {
    UniformForceRun r;
    r.first = i;
    r.last = i + 1;
    r.uniform = i >= b && i < n - b;
    r.f = system.load(i);
    r.d0 = damped ? forces.half_damping[b][i] : 0.;
    r.scale = scale[i];
    r.k0 = forces.stiffness[b][i];
    for (int o = 1; o <= b && r.uniform; ++o)
    {
      r.upper[o - 1] = forces.stiffness[b + o][i];
      r.lower[o - 1] = forces.stiffness[b + o][i - o];
    }
    return r;
  };
  const auto same_stiffness = [](const UniformForceRun& x, const UniformForceRun& y)
  {
    return x.uniform && y.uniform && x.k0 == y.k0 &&
           std::equal(x.upper, x.upper + 3, y.upper) &&
           std::equal(x.lower, x.lower + 3, y.lower);
  };
  // Runs of equal stiffness; the rows' own f, D/2 and scaling are kept aside.
  std::vector<ForceException> own(n);
  for (int i = 0; i < n; ++i)
  {
    const UniformForceRun r = coefficients(i);
    own[i] = {i, r.f, r.d0, r.scale};
    if (!uniform_runs.empty() && same_stiffness(uniform_runs.back(), r))
      uniform_runs.back().last = i + 1;
    else
      uniform_runs.push_back(r);
  }
  const auto same_values = [](const ForceException& x, const ForceException& y)
  { return x.f == y.f && x.d0 == y.d0 && x.scale == y.scale; };
  // A run takes the values most of its rows have (the wire's); the rows with
  // others become its exceptions, unless they are more than one in eight.
  for (UniformForceRun& r : uniform_runs)
  {
    if (!r.uniform || r.last - r.first < 8)
    {
      r.uniform = false;
      continue;
    }
    // The majority value by Boyer-Moore voting, then a count to confirm it.
    int candidate = r.first, votes = 0;
    for (int i = r.first; i < r.last; ++i)
    {
      if (votes == 0)
        candidate = i;
      votes += same_values(own[i], own[candidate]) ? 1 : -1;
    }
    const std::size_t first_exception = force_exceptions.size();
    for (int i = r.first; i < r.last; ++i)
      if (!same_values(own[i], own[candidate]))
        force_exceptions.push_back(own[i]);
    const int exceptions = force_exceptions.size() - first_exception;
    if (8 * exceptions > r.last - r.first)
    {
      force_exceptions.resize(first_exception);
      r.uniform = false;
      continue;
    }
    r.f = own[candidate].f;
    r.d0 = own[candidate].d0;
    r.scale = own[candidate].scale;
    r.first_exception = first_exception;
    r.last_exception = force_exceptions.size();
  }
  // Rows that are not in a uniform run are done one by one: merge them.
  std::vector<UniformForceRun> merged;
  for (const UniformForceRun& r : uniform_runs)
  {
    if (!r.uniform && !merged.empty() && !merged.back().uniform)
      merged.back().last = r.last;
    else
      merged.push_back(r);
  }
  uniform_runs.swap(merged);
  for (UniformForceRun& r : uniform_runs)
  {
    r.reach = 1;
    for (int o = 2; o <= b; ++o)
      if (r.upper[o - 1] != 0. || r.lower[o - 1] != 0.)
        r.reach = o;
    r.symmetric = std::equal(r.upper, r.upper + 3, r.lower);
  }
  // Worth it only with long runs on average.
  if (uniform_runs.size() * 32 > static_cast<std::size_t>(n))
  {
    uniform_runs.clear();
    force_exceptions.clear();
  }
  // DisjointFixedConstraints predicts its rows again from their final a.
  if (disjoint.used())
  {
    std::vector<bool> predicted_again(n, false);
    for (const unsigned int j : fixed_rows.index)
      predicted_again[j] = true;
    for (ForceException& x : force_exceptions)
      x.predict = !predicted_again[x.row];
  }
}

void HalfExplicitIntegrator::refresh_prediction()
{
  const double* __restrict qq = q.begin();
  const double* __restrict vv = v.begin();
  const double* __restrict vp = previous->begin();
  const double* __restrict aa = a.begin();
  double* __restrict qn = q_new.begin();
  double* __restrict vn = v_new.begin();
  const auto refresh = [&](const unsigned int i)
  { predict_unconstrained(i, aa[i], 2. * dt, 0.5 * dt, qq, vv, vp, qn, vn); };
  for (const unsigned int i : constant_refresh_rows)
    refresh(i);
  const auto& sn = at_n.states();
  for (const auto* list : {&moving, &compliant})
    for (const unsigned int c : *list)
      for (const unsigned int i : sn[c].G.index)
        refresh(i);
}

void HalfExplicitIntegrator::compute_update(const std::vector<unsigned int>& A)
{
  const auto& sn = at_n.states();
  const auto& sh = at_half.states();
  const auto& s1 = at_next.states();
  // Unconstrained part: v* = v_{n-1} + 2 dt a_n, q* = q_n + dt (v_n + v*)/2
  // (already there when compute_forces() predicted it).
  if (!predicted)
    predict_all(static_cast<int>(q.size()), a.begin(), 2. * dt, 0.5 * dt, q.begin(),
                v.begin(), previous->begin(), q_new.begin(), v_new.begin());
  split(A, keep, moving_active);
  const unsigned int mF = fixed.size(), p = moving_active.size();
  if (disjoint.used())
    solve_disjoint_position_and_velocity_level(sn, sh, s1);
  else
  {
    if (mF + p > 0)
      solve_position_and_velocity_level(sn, sh, s1);
    for (unsigned int k = 0; k < fixed.size(); ++k) // (those accept() reads)
      gaps[fixed[k]] = active_set.reads_gap(fixed[k])
                           ? fixed_rows.dot(k, q_new.begin()) + fixed_rows.offset[k]
                           : 0.;
  }
  for (const auto* list : {&moving, &compliant})
    for (const unsigned int i : *list)
      gaps[i] = s1[i].position_residual(q_new);
}
void HalfExplicitIntegrator::solve_position_and_velocity_level(
    const std::vector<ConstraintState>& sn, const std::vector<ConstraintState>& sh,
    const std::vector<ConstraintState>& s1)
{
  const bool settled = find_corrected_fixed();
  if (settled && corrected_fixed.size() <= max_corrected_subset)
  {
    solve_corrected_position_and_velocity_level(sn, sh, s1);
    return;
  }
  fixed_mass.select(keep);
  const unsigned int mF = fixed.size(), p = moving_active.size();
  const double h = dt;
  // Unknowns (eta_F, mu_F | eta_C, mu_C), rows g = 0 and dg/dt = 0 at t_{n+1}.
  position_workspace.prepare(2 * mF, 2 * p);
  dealii::Vector<double>& x = position_workspace.x;
  dealii::Vector<double>& y = position_workspace.y;
  // The fixed rows (G_t, z_t are 0).
  for (unsigned int k = 0; k < mF; ++k)
    if (keep[k])
      set_fixed_residuals(k, k, mF, x);
  fill_position_border(s1, mF,
                       [&](const MovingColumns& X, const auto& visit)
                       {
                         for (const unsigned int k : X.near_M)
                           if (keep[k])
                             visit(k, k);
                       });
  // The fixed block [h^2 S, h S; 2h S, 0] (S = G_F M^-1 G_F^T) by two solves with S:
  // eta = S^-1 r_v / (2h), mu = S^-1 r_g / h - h eta. The halves r_g, r_v of
  // all right-hand sides go through S side by side (four at a time).
  std::vector<dealii::Vector<double>>& halves = position_workspace.halves;
  std::vector<dealii::Vector<double>*>& half_pointers = position_workspace.half_pointers;
  const auto solve_all = [&](const std::vector<dealii::Vector<double>*>& xs)
  {
    if (halves.size() < 2 * xs.size())
      halves.resize(2 * xs.size());
    half_pointers.clear();
    for (std::size_t j = 0; j < xs.size(); ++j)
    {
      dealii::Vector<double>&g = halves[2 * j], &w = halves[2 * j + 1];
      if (g.size() != mF)
      {
        g.reinit(mF, true);
        w.reinit(mF, true);
      }
      const double* r = xs[j]->begin();
      std::copy(r, r + mF, g.begin());
      std::copy(r + mF, r + 2 * mF, w.begin());
      half_pointers.push_back(&g);
      half_pointers.push_back(&w);
    }
    fixed_mass.solve(half_pointers);
    for (std::size_t j = 0; j < xs.size(); ++j)
    {
      // Raw restrict pointers: the loop vectorises (the divisions too).
      double* __restrict r = xs[j]->begin();
      const double* __restrict g = halves[2 * j].begin();
      const double* __restrict w = halves[2 * j + 1].begin();
      for (unsigned int k = 0; k < mF; ++k)
      {
        const double eta = w[k] / (2. * h);
        r[k] = eta;
        r[mF + k] = g[k] / h - h * eta;
      }
    }
  };
  solve_bordered(solve_all, position_workspace.B, position_workspace.C,
                 position_workspace.D, x, y, position_workspace.rhs,
                 position_workspace.batch, t + dt, "position/velocity level");

  // q += M^-1 (h^2 G^T eta + h G_t^T eta + h G^T mu), v += M^-1 2h G^T eta:
  // the fixed rows' truncated columns M^-1 G^T (their G_t = 0).
  factors.assign(mF, 0.);
  factors_v.assign(mF, 0.);
  for (unsigned int k = 0; k < mF; ++k)
    if (keep[k])
    {
      const double eta = x(k), mu = x(mF + k);
      factors[k] = h * h * eta + h * mu;
      factors_v[k] = 2. * h * eta;
    }
  if (settled)
    for (unsigned int k = 0; k < mF; ++k)
      if (!correction_kept[k])
        factors[k] = factors_v[k] = 0.;
  fixed_mass.add_columns(factors, q_new, factors_v, v_new);
  add_moving_position_corrections(sn, sh);
}

void HalfExplicitIntegrator::solve_corrected_position_and_velocity_level(
    const std::vector<ConstraintState>& sn, const std::vector<ConstraintState>& sh,
    const std::vector<ConstraintState>& s1)
{
  const unsigned int nL = corrected_fixed.size(), p = moving_active.size();
  const double h = dt;
  fixed_mass.factorize_subset(corrected_fixed);
  position_workspace.prepare(2 * nL, 2 * p);
  dealii::Vector<double>& x = position_workspace.x;
  for (unsigned int l = 0; l < nL; ++l)
  {
    const unsigned int k = corrected_fixed[l];
    corrected_slot[k] = l;
    set_fixed_residuals(k, l, nL, x);
  }
  // The fixed constraints that a moving column reaches are all corrected.
  fill_position_border(s1, nL,
                       [&](const MovingColumns& X, const auto& visit)
                       {
                         for (const unsigned int k : X.near_M)
                           if (keep[k])
                             visit(corrected_slot[k], k);
                       });
  // The fixed block [h^2 S, h S; 2h S, 0] restricted to R: eta = S_RR^-1 r_v /
  // (2h), mu = S_RR^-1 r_g / h - h eta.
  solve_bordered(
      [&](const std::vector<dealii::Vector<double>*>& xs)
      {
        for (dealii::Vector<double>* r : xs)
        {
          fixed_mass.solve_subset(r->begin());
          fixed_mass.solve_subset(r->begin() + nL);
          for (unsigned int l = 0; l < nL; ++l)
          {
            const double eta = (*r)(nL + l) / (2. * h);
            (*r)(nL + l) = (*r)(l) / h - h * eta;
            (*r)(l) = eta;
          }
        }
      },
      position_workspace.B, position_workspace.C, position_workspace.D, x,
      position_workspace.y, position_workspace.rhs, position_workspace.batch, t + dt,
      "position/velocity level");
  factors.assign(fixed.size(), 0.);
  factors_v.assign(fixed.size(), 0.);
  for (unsigned int l = 0; l < nL; ++l)
  {
    const unsigned int k = corrected_fixed[l];
    factors[k] = h * h * x(l) + h * x(nL + l);
    factors_v[k] = 2. * h * x(l);
    corrected_slot[k] = -1;
  }
  fixed_mass.add_columns(factors, q_new, factors_v, v_new);
  add_moving_position_corrections(sn, sh);
}

void HalfExplicitIntegrator::set_fixed_residuals(const unsigned int k,
                                                 const unsigned int slot,
                                                 const unsigned int half,
                                                 dealii::Vector<double>& x) const
{
  x(slot) = -(fixed_rows.dot(k, q_new.begin()) + fixed_rows.offset[k]);
  x(half + slot) = -fixed_rows.dot(k, v_new.begin());
}

bool HalfExplicitIntegrator::find_corrected_fixed()
{
  settled_count = 0;
  if (!settling || step_number < history_start + 2 || !pending_impulse.empty())
    return false;
  // The sources: the held fixed constraints that are not settled, and those
  // that a moving constraint's columns M^-1 G^T reach; with them, the
  // constraints S couples to them beyond the unit round-off.
  const unsigned int mF = fixed.size();
  settle_sources.clear();
  for (unsigned int k = 0; k < mF; ++k)
    if (keep[k] && !(force_keep[k] && active_now[fixed[k]] && reported.active[fixed[k]]))
      settle_sources.push_back(k);
  gather_near_fixed(&MovingColumns::near_M);
  settle_sources.insert(settle_sources.end(), near_fixed.begin(), near_fixed.end());
  correction_kept.assign(mF, false);
  constexpr double unit_roundoff = 0.5 * std::numeric_limits<double>::epsilon();
  fixed_mass.reach_from(settle_sources, keep, unit_roundoff, correction_kept);
  // A settled constraint's turn to be corrected: its multipliers are the
  // round-off its row gathered since, and its neighbours' share of them less.
  corrected_fixed.clear();
  for (unsigned int k = 0; k < mF; ++k)
  {
    correction_kept[k] =
        correction_kept[k] || (step_number + k) % settled_refresh_period == 0;
    if (keep[k] && correction_kept[k])
      corrected_fixed.push_back(k);
    settled_count += keep[k] && !correction_kept[k];
  }
  return true;
}

void HalfExplicitIntegrator::add_moving_position_corrections(
    const std::vector<ConstraintState>& sn, const std::vector<ConstraintState>& sh)
{
  const unsigned int p = moving_active.size();
  const dealii::Vector<double>& y = position_workspace.y;
  const double h = dt;
  for (unsigned int c = 0; c < p; ++c)
  {
    const unsigned int j = moving_active[c];
    const MovingColumns& X = columns[position[j]];
    const double eta = y(c), mu = y(p + c);
    const RowRanges& reach = X.reach_M;
    add_moving_column(mass_inverse, sn[j].G, X.P, X.local_M, reach, h * h * eta, q_new);
    add_moving_column(mass_inverse, sh[j].G_t, X.Q, X.local_M, reach, h * eta, q_new);
    add_moving_column(mass_inverse, sh[j].G, X.R, X.local_M, reach, h * mu, q_new);
    add_moving_column(mass_inverse, sn[j].G, X.P, X.local_M, reach, 2. * h * eta, v_new);
  }
}

template <typename NearFixed>
void HalfExplicitIntegrator::fill_position_border(const std::vector<ConstraintState>& s1,
                                                  const unsigned int half,
                                                  const NearFixed& near_fixed_of)
{
  const unsigned int p = moving_active.size();
  const double h = dt;
  dealii::Vector<double>& y = position_workspace.y;
  std::vector<dealii::Vector<double>>& B = position_workspace.B;
  std::vector<dealii::Vector<double>>& C = position_workspace.C;
  dealii::FullMatrix<double>& D = position_workspace.D;
  for (unsigned int c = 0; c < p; ++c)
  {
    const ConstraintState& sc = s1[moving_active[c]];
    y(c) = -(sc.G.dot(q_new) + sc.z);
    y(p + c) = -(sc.G_t.dot(q_new) + sc.G.dot(v_new) + sc.z_t);
    const MovingColumns& X = columns[position[moving_active[c]]];
    // Fixed rows against the moving unknowns (their G_t = 0), and the moving
    // rows against the fixed unknowns through U, V (M symmetric: G_c M^-1 G_l^T = G_l
    // U_c). The fixed rows not near the columns meet them in zeros. Fixed
    // constraint k has the unknowns (slot, half + slot).
    near_fixed_of(X,
                  [&](const unsigned int slot, const unsigned int k)
                  {
                    const auto G = [&](const dealii::Vector<double>& column)
                    { return fixed_rows.dot(k, column.begin()); };
                    const double GP = G(X.P), GQ = G(X.Q), GR = G(X.R);
                    B[c](slot) = h * h * GP + h * GQ;
                    B[c](half + slot) = 2. * h * GP;
                    B[p + c](slot) = h * GR;
                    const double GU = G(X.U), GV = G(X.V);
                    C[c](slot) = h * h * GU;
                    C[c](half + slot) = h * GU;
                    C[p + c](slot) = h * h * GV + 2. * h * GU;
                    C[p + c](half + slot) = h * GV;
                  });
    // Moving rows against the moving unknowns, as (40) reads.
    for (unsigned int r = 0; r < p; ++r)
    {
      const ConstraintState& s = s1[moving_active[r]];
      const double GP = s.G.dot(X.P), GQ = s.G.dot(X.Q), GR = s.G.dot(X.R);
      const double GtP = s.G_t.dot(X.P), GtQ = s.G_t.dot(X.Q), GtR = s.G_t.dot(X.R);
      D(r, c) = h * h * GP + h * GQ;
      D(r, p + c) = h * GR;
      D(p + r, c) = h * h * GtP + h * GtQ + 2. * h * GP;
      D(p + r, p + c) = h * GtR;
    }
  }
}

void HalfExplicitIntegrator::solve_disjoint_position_and_velocity_level(
    const std::vector<ConstraintState>& sn, const std::vector<ConstraintState>& sh,
    const std::vector<ConstraintState>& s1)
{
  disjoint.select_position(keep, keep_version);
  const unsigned int p = moving_active.size();
  const double h = dt;
  const bool projected = projected_early;
  projected_early = false;
  if (p > 0)
  {
    // The moving constraints' eta, mu first, bordered by the fixed ones on
    // their unknowns only; their corrections go into q*, v*, and every fixed
    // constraint's eta, mu follow from its own row (DisjointFixedConstraints).
    gather_near_fixed(&MovingColumns::near_M);
    const unsigned int nL = near_fixed.size();
    position_workspace.prepare(2 * nL, 2 * p);
    dealii::Vector<double>& x = position_workspace.x;
    for (unsigned int l = 0; l < nL; ++l)
      set_fixed_residuals(near_fixed[l], l, nL, x);
    fill_position_border(s1, nL,
                         [&](const MovingColumns&, const auto& visit)
                         {
                           for (unsigned int l = 0; l < nL; ++l)
                             visit(l, near_fixed[l]);
                         });
    // The fixed block [h^2 S, h S; 2h S, 0] of one constraint: eta = S^-1 r_v /
    // (2h), mu = S^-1 r_g / h - h eta.
    solve_bordered(
        [&](const std::vector<dealii::Vector<double>*>& xs)
        {
          for (dealii::Vector<double>* r : xs)
            for (unsigned int l = 0; l < nL; ++l)
            {
              const double inverse = disjoint.mass_inverse(near_fixed[l]);
              const double eta = (*r)(nL + l) * inverse / (2. * h);
              (*r)(nL + l) = (*r)(l)*inverse / h - h * eta;
              (*r)(l) = eta;
            }
        },
        position_workspace.B, position_workspace.C, position_workspace.D, x,
        position_workspace.y, position_workspace.rhs, position_workspace.batch, t + dt,
        "position/velocity level");
    add_moving_position_corrections(sn, sh);
  }
  if (projected)
    disjoint.project(q_new.begin(), v_new.begin(), h, gaps, deferred_fixed);
  else
    disjoint.project(q_new.begin(), v_new.begin(), h, gaps);
}

void HalfExplicitIntegrator::prepare_step()
{
  at_n.at(t);
  at_half.at(t + 0.5 * dt, 1); // (40) needs G and G_t at t_{n+1/2} and t_{n+1}
  at_next.at(t + dt, 1);
  const bool fuse = smoothed_mass_inverse.factorised() && !moving.empty();
  if (fuse)
  {
    // a*'s right-hand side: compute_moving_columns() solves it beside Y.
    free_acceleration.reinit(system.n_dofs(), true);
    std::fill(lambda.begin(), lambda.end(), 0.);
    compute_compliant_forces();
    unscaled_forces(free_acceleration.begin());
  }
  compute_moving_columns();
  free_acceleration_ready = fuse;
  free_acceleration_taken = false;
}

void HalfExplicitIntegrator::advance()
{
  prepare_step();
  active_set.start(active_now);
  for (;;)
  {
    // g^(II): touching ones carry no force
    compute_acceleration(active_set.force_indices(), &active_set.active_indices());
    compute_update(active_set.active_indices());
    if (active_set.accept(gaps, lambda, t + dt, step_number + 1))
      break;
    ++stats.active_set_iterations;
  }
  free_acceleration_ready = false;
  reset_moving_columns();
  stats.active_set_changes += active_set.changes_in_step();
  // A constraint that closed in this step (taken without it: it had no
  // contact at t_n, so no force lambda_n) is an impact at t_{n+1}: q_{n+1},
  // v_{n+1} are projected onto the holding constraints; P is the impulse.
  std::vector<double> impulse;
  std::vector<unsigned int> separated;
  const bool impact = active_set.impact_in_step();
  if (impact)
  {
    jump = v_new;
    ImpactProjection::Result r = impacts.project(
        at_next.states(), active_set.holding_indices(), t + dt, lambda, dt, q_new, v_new);
    impulse.swap(r.impulse);
    separated.swap(r.separated);
    jump.sadd(-1., 1., v_new); // v+ - v- = M^-1 G^T P
  }

  // Report t_n: q_n, v_n satisfy the constraints of J_n; lambda_n belongs to
  // the set J_{n+1} of this step (a constraint closing in this step already
  // carries its impact force). Then move on to t_{n+1}.
  reported.t = t;
  reported.q.swap(q); // q_n
  q.swap(q_new);      // q_{n+1}
  // v_n is both the reported velocity and v_{n-1} of the next step: one
  // vector, reported.v, without a copy.
  reported.v.swap(v); // v_n
  v.swap(v_new);      // v_{n+1}
  previous = &reported.v;
  if (impact)
  {
    // The two-step update (40) takes v_{n+2} from v_n: with the jump added
    // there as well, the impact is not forgotten at the next step (nor
    // undone when the constraint separates again). A restart from the state
    // after the impact (v_n := v_{n+1} - dt a_{n+1}) would do the same, but
    // its one-step map amplifies the stiffest modes by up to sqrt(3) when
    // impacts follow each other closely.
    v_prev = reported.v;
    v_prev += jump;
    previous = &v_prev;
  }
  reported.a.swap(a);
  reported.lambda = lambda;
  reported.active = active_now;
  reported.impulse.swap(pending_impulse); // the impact at t_n, if any
  pending_impulse.swap(impulse);
  active_now = active_set.active();
  for (const unsigned int i : compliant) // explicit: engaged at t_n, not iterated
    active_now[i] = reported.active[i];
  if (impact)
    for (const unsigned int i : separated) // their impulse would pull: they separate
      active_now[i] = false;
  t += dt;
  ++step_number;
  ++stats.steps;
}

void HalfExplicitIntegrator::finish()
{
  // Step 1 alone at the final time: a_N and lambda_N with the current active
  // set, on acceleration level as in a step (Sec. 5.3): a rigid unilateral
  // constraint with lambda_N < 0 holds without force (it touches: g = dg/dt
  // = 0 at t_N come from the step that reached t_N), and step 1 is repeated.
  std::vector<unsigned int> A;
  for (unsigned int i = 0; i < active_now.size(); ++i)
    if (active_now[i] && !system.constraints[i]->is_compliant())
      A.push_back(i);
  for (;;)
  {
    prepare_step();
    compute_acceleration(A);
    free_acceleration_ready = false;
    reset_moving_columns();
    const auto pulls = [&](const unsigned int i)
    { return system.constraints[i]->is_unilateral() && lambda[i] < 0.; };
    const auto kept = std::remove_if(A.begin(), A.end(), pulls);
    if (kept == A.end())
      break;
    A.erase(kept, A.end());
  }
  if (previous == &reported.v) // v_{n-1} stays the integrator's own
  {
    v_prev = reported.v;
    previous = &v_prev;
  }
  reported.t = t;
  reported.q = q;
  reported.v = v;
  reported.a = a;
  reported.lambda = lambda;
  reported.active = active_now;
  reported.impulse = pending_impulse;
}

void HalfExplicitIntegrator::save(CheckpointOut& archive) const
{
  // a_n and lambda_n are recomputed from these in the next step (39).
  archive << t << step_number << q << v << *previous << active_now << reported
          << pending_impulse;
  save_statistics(archive);
}

void HalfExplicitIntegrator::load(CheckpointIn& archive)
{
  archive >> t >> step_number >> q >> v >> v_prev >> active_now >> reported >>
      pending_impulse;
  previous = &v_prev;
  load_statistics(archive);
  if (!std::isfinite(t))
    throw InputError("the time t_n is not finite");
  check_loaded(q, system.n_dofs(), "q_n");
  check_loaded(v, system.n_dofs(), "v_n");
  check_loaded(v_prev, system.n_dofs(), "v_{n-1}");
  check_loaded(active_now, "the active set");
  check_loaded(reported, "the last reported state");
  check_loaded_steps(step_number);
}

IntegratorEntry HalfExplicitIntegrator::registry_entry()
{
  IntegratorEntry e;
  e.name = "half-explicit";
  e.description = "the reversible half-explicit method (39)-(41) (explicit in the "
                  "unknowns, stable for dt < 2/omega_max)";
  e.explicit_step_limit = true;
  e.writes_checkpoints = true;
  e.locates_events = false;
  e.create = [](const SemiDiscreteSystem& system, const TimeIntegrationParameters& p)
  {
    return std::make_unique<HalfExplicitIntegrator>(system, p.time_step,
                                                    p.max_active_set_iterations);
  };
  return e;
}
} // namespace pantocat
