#include <pantocat/constrained/unconstrained_prediction.h>
#include <pantocat/constrained_fast/fast_half_explicit_step_system.h>

#include <algorithm>
#include <type_traits>

// The forces of the acceleration level (39), (41) of FastHalfExplicitStepSystem:
// f - K q_n - D (v_{n-1} + v_n)/2 swept by the diagonals of K and D/2, with
// the scaling of (M + h/2 D)^-1 and the prediction of (40) fused in where
// M + h/2 D is diagonal, and the runs of rows with equal coefficients.

namespace pantocat
{
void FastHalfExplicitStepSystem::build_force_diagonals()
{
  const unsigned int n = system.n_dofs();
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
 * from their final a (FastHalfExplicitStepSystem::refresh_prediction()).
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

void FastHalfExplicitStepSystem::predict_every_row()
{
  predict_all(static_cast<int>(q_n().size()), a_n().begin(), 2. * h, 0.5 * h,
              q_n().begin(), v_n().begin(), step.v_previous->begin(), next_q().begin(),
              next_v().begin());
}

const double* FastHalfExplicitStepSystem::load_at_time_n()
{
  if (!system.has_time_dependent_load())
    return system.load.begin();
  system.load_at(step.t, load_now);
  return load_now.begin();
}

void FastHalfExplicitStepSystem::compute_forces()
{
  const int n = q_n().size(), b = forces.bandwidth;
  const double* __restrict qq = q_n().begin();
  const double* __restrict vv = v_n().begin();
  const double* __restrict vp = step.v_previous->begin();
  double* __restrict out = a_n().begin();
  // Damping is diagonal but for a few rows (a lumped pantograph's dampers):
  // the fused sweep with the diagonal, then those entries.
  const dealii::Vector<double>* scaling = smoothed_mass_inverse.row_scaling();
  if (forces.listed_damping.size() <= 16 && b >= 1 && b <= 3 &&
      forces.symmetric_stiffness && scaling)
  {
    const double* d0 = forces.half_damping[b].data();
    const double* f = load_at_time_n();
    const double* scale = scaling->begin();
    double* qn = next_q().begin();
    double* vn = next_v().begin();
    if (!uniform_runs_built)
      build_uniform_runs(scale);
    const std::vector<UniformForceRun>* runs =
        uniform_runs.empty() || system.has_time_dependent_load() ? nullptr
                                                                 : &uniform_runs;
    const auto sweep = [&](auto damped)
    {
      constexpr bool D = decltype(damped)::value;
      if (b == 1)
        banded_forces<1, D, true>(n, f, forces.stiffness, d0, scale, qq, vp, vv, out, h,
                                  qn, vn, runs, force_exceptions.data());
      else if (b == 2)
        banded_forces<2, D, true>(n, f, forces.stiffness, d0, scale, qq, vp, vv, out, h,
                                  qn, vn, runs, force_exceptions.data());
      else
        banded_forces<3, D, true>(n, f, forces.stiffness, d0, scale, qq, vp, vv, out, h,
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
    smoothed_mass_inverse.apply_coupled_rows(a_n());
    return;
  }
  predicted = false;
  if (free_acceleration_ready)
  {
    if (free_acceleration_taken)
      solve_free_acceleration();
    a_n().swap(free_acceleration);
    free_acceleration_taken = true;
    return;
  }
  unscaled_forces(out);
  smoothed_mass_inverse.apply(a_n());
}

void FastHalfExplicitStepSystem::solve_free_acceleration()
{
  free_acceleration.reinit(system.n_dofs(), true);
  unscaled_forces(free_acceleration.begin());
  smoothed_mass_inverse.factorised()->solve(free_acceleration);
}

void FastHalfExplicitStepSystem::unscaled_forces(double* out)
{
  const double* __restrict qq = q_n().begin();
  const double* __restrict vv = v_n().begin();
  const double* __restrict vp = step.v_previous->begin();
  const double* f = load_at_time_n();
  force_sweep.apply(f, qq, vp, vv, out);
  add_compliant_loads(out, nullptr);
}

void FastHalfExplicitStepSystem::build_uniform_runs(const double* scale)
{
  uniform_runs.clear();
  force_exceptions.clear();
  uniform_runs_built = true;
  if (system.has_time_dependent_load())
    return;
  const int n = system.n_dofs(), b = forces.bandwidth;
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
  take_majority_values(own);
  merge_and_finish_runs();
}

void FastHalfExplicitStepSystem::take_majority_values(
    const std::vector<ForceException>& own)
{
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
}

void FastHalfExplicitStepSystem::merge_and_finish_runs()
{
  const int n = system.n_dofs(), b = forces.bandwidth;
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

void FastHalfExplicitStepSystem::refresh_prediction()
{
  const double* __restrict qq = q_n().begin();
  const double* __restrict vv = v_n().begin();
  const double* __restrict vp = step.v_previous->begin();
  const double* __restrict aa = a_n().begin();
  double* __restrict qn = next_q().begin();
  double* __restrict vn = next_v().begin();
  const auto refresh = [&](const unsigned int i)
  { predict_unconstrained(i, aa[i], 2. * h, 0.5 * h, qq, vv, vp, qn, vn); };
  for (const unsigned int i : constant_refresh_rows)
    refresh(i);
  const auto& sn = *step.at_n;
  for (const auto* list : {&moving, &compliant})
    for (const unsigned int c : *list)
      for (const unsigned int i : sn[c].G.index)
        refresh(i);
}

} // namespace pantocat
