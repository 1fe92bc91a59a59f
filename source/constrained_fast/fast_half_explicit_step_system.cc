#include <pantocat/base/input_error.h>
#include <pantocat/constrained_fast/fast_half_explicit_step_system.h>
#include <pantocat/constrained_fast/multiplier_system.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace pantocat
{

FastHalfExplicitStepSystem::FastHalfExplicitStepSystem(const SemiDiscreteSystem& system,
                                                       const double h)
    : HalfExplicitStepSystem(system, h)
{
  const unsigned int n = system.n_dofs(), m = system.n_constraints();
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
  for (const unsigned int i : fixed) // constant rows: evaluated once
  {
    ConstraintState row;
    system.constraints[i]->evaluate(0., row, 0);
    fixed_rows.push_back(row.G);
    fixed_rows.offset.push_back(row.z);
    fixed_row_list.push_back(row.G);
  }
  mass_inverse.initialize(system.mass, system.mass_is_diagonal, "mass matrix M");
  factorize();
  build_force_diagonals();
  is_moving.assign(m, false);
  for (const unsigned int i : moving)
    is_moving[i] = true;
  fixed_by_unknown.build(fixed_rows, n); // find_fixed_near()
  near_mark.assign(fixed.size(), false);
  corrected_slot.assign(fixed.size(), -1);
  take_disjoint_fixed_constraints();
}

void FastHalfExplicitStepSystem::take_disjoint_fixed_constraints()
{
  disjoint.initialize(fixed_rows, fixed_rows.offset, fixed, smoothed_mass_inverse,
                      mass_inverse, system.n_dofs());
  project_now.assign(fixed.size(), true);
  // The rows whose a changes after the sweep with a constant pattern: the
  // coupled rows, and the rows of the fixed constraints (their columns
  // (M + h/2 D)^-1 G^T live there and on the coupled rows when it is
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

void FastHalfExplicitStepSystem::factorize()
{
  // (M + h/2 D) of (39) with (41); diagonal when M and D are.
  dealii::SparseMatrix<double> smoothed(*system.sparsity);
  smoothed.copy_from(system.mass);
  smoothed.add(0.5 * h, system.damping);
  bool diagonal = system.mass_is_diagonal;
  for (unsigned int i = 0; diagonal && i < system.n_dofs(); ++i)
    for (auto it = system.damping.begin(i); diagonal && it != system.damping.end(i); ++it)
      diagonal = it->column() == i || it->value() == 0.;
  smoothed_mass_inverse.initialize(smoothed, diagonal, "matrix M + dt/2 D");

  // The Schur complements of the rigid constraints with constant rows, once.
  std::vector<const SparseRow*> rows;
  for (const SparseRow& row : fixed_row_list)
    rows.push_back(&row);
  fixed_smoothed.initialize(rows, smoothed_mass_inverse, system.n_dofs(),
                            "matrix G (M + dt/2 D)^-1 G^T of the fixed constraints");
  fixed_mass.initialize(rows, mass_inverse, system.n_dofs(),
                        "matrix G M^-1 G^T of the fixed constraints");
}

void FastHalfExplicitStepSystem::set_time_step(const double time_step)
{
  h = time_step;
  uniform_runs_built = false; // the scaling of (M + h/2 D)^-1 changes
  factorize();
  take_disjoint_fixed_constraints();
}

void FastHalfExplicitStepSystem::find_fixed_near(
    std::initializer_list<const SparseRow*> rows, const MassInverse& A, const bool local,
    const RowRanges& reach, std::vector<unsigned int>& near)
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

void FastHalfExplicitStepSystem::compute_moving_columns()
{
  const auto& sn = *step.at_n;
  const auto& sh = *step.at_half;
  const auto& s1 = *step.at_next;
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
        // M diagonal, M + h/2 D banded (the FDM with Rayleigh damping): a* on
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

void FastHalfExplicitStepSystem::compute_factorised_columns(
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

void FastHalfExplicitStepSystem::compute_local_column(const SparseDirectSolver& W,
                                                      const SparseRow& G,
                                                      MovingColumns& x)
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

void FastHalfExplicitStepSystem::add_moving_column(
    const MassInverse& A, const SparseRow& row, const dealii::Vector<double>& column,
    const bool local, const RowRanges& reach, const double factor,
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

void FastHalfExplicitStepSystem::reset_moving_columns()
{
  if (smoothed_mass_inverse.factorised() && mass_inverse.factorised())
    return; // compute_factorised_columns() resets the rows it reached
  const auto& sn = *step.at_n;
  const auto& sh = *step.at_half;
  const auto& s1 = *step.at_next;
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

const FastHalfExplicitStepSystem::ActiveSplit&
FastHalfExplicitStepSystem::split_of(const std::vector<unsigned int>& A)
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

void FastHalfExplicitStepSystem::split(const std::vector<unsigned int>& A,
                                       std::vector<bool>& keep_fixed,
                                       std::vector<unsigned int>& moving_in_A)
{
  const ActiveSplit& s = split_of(A);
  keep_fixed = s.keep;
  moving_in_A = s.moving;
  keep_version = s.version;
}

void FastHalfExplicitStepSystem::MultiplierWorkspace::prepare(const unsigned int n_fixed,
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

void FastHalfExplicitStepSystem::add_compliant_loads(double* f,
                                                     const double* scaling) const
{
  const auto& sn = *step.at_n;
  for (const unsigned int i : compliant)
    if (multipliers()[i] != 0.)
    {
      const SparseRow& G = sn[i].G;
      for (std::size_t k = 0; k < G.size(); ++k)
      {
        const unsigned int j = G.index[k];
        f[j] += multipliers()[i] * G.value[k] * (scaling ? scaling[j] : 1.);
      }
    }
}

void FastHalfExplicitStepSystem::add_acceleration_multipliers(
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
      x(k) = -fixed_rows.dot(k, a_n().begin());
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
      step.t, "acceleration level");
  // a += (M + h/2 D)^-1 G^T lambda: the fixed rows' truncated columns.
  factors.assign(mF, 0.);
  for (unsigned int k = 0; k < mF; ++k)
    if (keep[k])
      factors[k] = multipliers()[fixed[k]] = x(k);
  fixed_smoothed.add_columns(factors, a_n());
  add_moving_acceleration_forces();
}

template <typename NearFixed>
void FastHalfExplicitStepSystem::fill_acceleration_border(const NearFixed& near_fixed_of)
{
  const auto& sn = *step.at_n;
  const unsigned int p = moving_active.size();
  dealii::Vector<double>& y = acceleration_workspace.y;
  std::vector<dealii::Vector<double>>& B = acceleration_workspace.B;
  std::vector<dealii::Vector<double>>& C = acceleration_workspace.C;
  dealii::FullMatrix<double>& D = acceleration_workspace.D;
  // The moving constraints border the fixed ones: B = G_F Y_c, C = B^T
  // ((M + h/2 D) is symmetric), D = G_c Y_c'; g^(II) = G a + 2 G_t v + G_tt
  // q + z_tt = 0 at t_n.
  for (unsigned int c = 0; c < p; ++c)
  {
    const ConstraintState& s = sn[moving_active[c]];
    y(c) = -(s.G.dot(a_n()) + 2. * s.G_t.dot(v_n()) + s.G_tt.dot(q_n()) + s.z_tt);
    const MovingColumns& X = columns[position[moving_active[c]]];
    near_fixed_of(X, [&](const unsigned int slot, const unsigned int k)
                  { B[c](slot) = fixed_rows.dot(k, X.Y.begin()); });
    for (unsigned int r = 0; r < p; ++r)
      D(r, c) = sn[moving_active[r]].G.dot(X.Y);
  }
  for (unsigned int c = 0; c < p; ++c)
    C[c] = B[c];
}

void FastHalfExplicitStepSystem::add_moving_acceleration_forces()
{
  const auto& sn = *step.at_n;
  const dealii::Vector<double>& y = acceleration_workspace.y;
  for (unsigned int c = 0; c < moving_active.size(); ++c)
  {
    const unsigned int i = moving_active[c];
    multipliers()[i] = y(c);
    const MovingColumns& X = columns[position[i]];
    add_moving_column(smoothed_mass_inverse, sn[i].G, X.Y, X.local_Y, X.reach_Y, y(c),
                      a_n());
  }
}

void FastHalfExplicitStepSystem::gather_near_fixed(
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

void FastHalfExplicitStepSystem::add_disjoint_acceleration_multipliers()
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
      x(l) = -fixed_rows.dot(near_fixed[l], a_n().begin());
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
        acceleration_workspace.batch, step.t, "acceleration level");
    add_moving_acceleration_forces();
  }
  const DisjointFixedConstraints::Prediction prediction{
      q_n().begin(),    v_n().begin(),    step.v_previous->begin(),
      next_q().begin(), next_v().begin(), h};
  projected_early = predicted && update_set;
  if (!projected_early)
  {
    disjoint.accelerate(a_n().begin(), multipliers(), predicted ? &prediction : nullptr);
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
  disjoint.accelerate(a_n().begin(), multipliers(), &prediction, &project_now,
                      &gaps_next());
  for (const unsigned int k : deferred_fixed)
    project_now[k] = true;
}

void FastHalfExplicitStepSystem::position_level(const std::vector<unsigned int>& A)
{
  const auto& sn = *step.at_n;
  const auto& sh = *step.at_half;
  const auto& s1 = *step.at_next;
  split(A, keep, moving_active);
  const unsigned int mF = fixed.size(), p = moving_active.size();
  if (disjoint.used())
    solve_disjoint_position_and_velocity_level(sn, sh, s1);
  else
  {
    if (mF + p > 0)
      solve_position_and_velocity_level(sn, sh, s1);
    for (unsigned int k = 0; k < mF; ++k)
      gaps_next()[fixed[k]] = fixed_rows.dot(k, next_q().begin()) + fixed_rows.offset[k];
  }
  for (const auto* list : {&moving, &compliant})
    for (const unsigned int i : *list)
      gaps_next()[i] = s1[i].position_residual(next_q());
}

void FastHalfExplicitStepSystem::solve_fixed_position_block(
    const std::vector<dealii::Vector<double>*>& xs)
{
  const unsigned int mF = fixed.size();
  std::vector<dealii::Vector<double>>& halves = position_workspace.halves;
  std::vector<dealii::Vector<double>*>& half_pointers = position_workspace.half_pointers;
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
}

void FastHalfExplicitStepSystem::solve_position_and_velocity_level(
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
  const auto solve_all = [&](const std::vector<dealii::Vector<double>*>& xs)
  { solve_fixed_position_block(xs); };
  solve_bordered(solve_all, position_workspace.B, position_workspace.C,
                 position_workspace.D, x, y, position_workspace.rhs,
                 position_workspace.batch, step.t + h, "position/velocity level");

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
  fixed_mass.add_columns(factors, next_q(), factors_v, next_v());
  add_moving_position_corrections(sn, sh);
}

void FastHalfExplicitStepSystem::solve_corrected_position_and_velocity_level(
    const std::vector<ConstraintState>& sn, const std::vector<ConstraintState>& sh,
    const std::vector<ConstraintState>& s1)
{
  const unsigned int nL = corrected_fixed.size(), p = moving_active.size();
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
      position_workspace.y, position_workspace.rhs, position_workspace.batch, step.t + h,
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
  fixed_mass.add_columns(factors, next_q(), factors_v, next_v());
  add_moving_position_corrections(sn, sh);
}

void FastHalfExplicitStepSystem::set_fixed_residuals(const unsigned int k,
                                                     const unsigned int slot,
                                                     const unsigned int half,
                                                     dealii::Vector<double>& x) const
{
  x(slot) = -(fixed_rows.dot(k, next_q().begin()) + fixed_rows.offset[k]);
  x(half + slot) = -fixed_rows.dot(k, next_v().begin());
}

bool FastHalfExplicitStepSystem::find_corrected_fixed()
{
  settled_count = 0;
  if (!settling || !step.active_before || !step.active_now)
    return false;
  const std::vector<bool>&before = *step.active_before, &now = *step.active_now;
  // The sources: the held fixed constraints that are not settled, and those
  // that a moving constraint's columns M^-1 G^T reach; with them, the
  // constraints S couples to them beyond the unit round-off.
  const unsigned int mF = fixed.size();
  settle_sources.clear();
  for (unsigned int k = 0; k < mF; ++k)
    if (keep[k] && !(force_keep[k] && now[fixed[k]] && before[fixed[k]]))
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
        correction_kept[k] || (step.number + k) % settled_refresh_period == 0;
    if (keep[k] && correction_kept[k])
      corrected_fixed.push_back(k);
    settled_count += keep[k] && !correction_kept[k];
  }
  return true;
}

void FastHalfExplicitStepSystem::add_moving_position_corrections(
    const std::vector<ConstraintState>& sn, const std::vector<ConstraintState>& sh)
{
  const unsigned int p = moving_active.size();
  const dealii::Vector<double>& y = position_workspace.y;
  for (unsigned int c = 0; c < p; ++c)
  {
    const unsigned int j = moving_active[c];
    const MovingColumns& X = columns[position[j]];
    const double eta = y(c), mu = y(p + c);
    const RowRanges& reach = X.reach_M;
    add_moving_column(mass_inverse, sn[j].G, X.P, X.local_M, reach, h * h * eta,
                      next_q());
    add_moving_column(mass_inverse, sh[j].G_t, X.Q, X.local_M, reach, h * eta, next_q());
    add_moving_column(mass_inverse, sh[j].G, X.R, X.local_M, reach, h * mu, next_q());
    add_moving_column(mass_inverse, sn[j].G, X.P, X.local_M, reach, 2. * h * eta,
                      next_v());
  }
}

template <typename NearFixed>
void FastHalfExplicitStepSystem::fill_position_border(
    const std::vector<ConstraintState>& s1, const unsigned int half,
    const NearFixed& near_fixed_of)
{
  const unsigned int p = moving_active.size();
  dealii::Vector<double>& y = position_workspace.y;
  std::vector<dealii::Vector<double>>& B = position_workspace.B;
  std::vector<dealii::Vector<double>>& C = position_workspace.C;
  dealii::FullMatrix<double>& D = position_workspace.D;
  for (unsigned int c = 0; c < p; ++c)
  {
    const ConstraintState& sc = s1[moving_active[c]];
    y(c) = -(sc.G.dot(next_q()) + sc.z);
    y(p + c) = -(sc.G_t.dot(next_q()) + sc.G.dot(next_v()) + sc.z_t);
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

void FastHalfExplicitStepSystem::solve_disjoint_position_and_velocity_level(
    const std::vector<ConstraintState>& sn, const std::vector<ConstraintState>& sh,
    const std::vector<ConstraintState>& s1)
{
  disjoint.select_position(keep, keep_version);
  const unsigned int p = moving_active.size();
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
        position_workspace.y, position_workspace.rhs, position_workspace.batch,
        step.t + h, "position/velocity level");
    add_moving_position_corrections(sn, sh);
  }
  if (projected)
    disjoint.project(next_q().begin(), next_v().begin(), h, gaps_next(), deferred_fixed);
  else
    disjoint.project(next_q().begin(), next_v().begin(), h, gaps_next());
}

void FastHalfExplicitStepSystem::start(const Step& new_step)
{
  step = new_step;
  const bool fuse = smoothed_mass_inverse.factorised() && !moving.empty();
  if (fuse)
  {
    // a*'s right-hand side: compute_moving_columns() solves it beside Y.
    free_acceleration.reinit(system.n_dofs(), true);
    unscaled_forces(free_acceleration.begin());
  }
  compute_moving_columns();
  free_acceleration_ready = fuse;
  free_acceleration_taken = false;
}

void FastHalfExplicitStepSystem::acceleration_level(
    const std::vector<unsigned int>& force_set, const std::vector<unsigned int>* next_set)
{
  update_set = next_set;
  for (const unsigned int i : fixed)
    multipliers()[i] = 0.;
  for (const unsigned int i : moving)
    multipliers()[i] = 0.;
  compute_forces();
  add_acceleration_multipliers(force_set);
  // The unconstrained part of (40), unless compute_forces() predicted it.
  if (predicted)
    refresh_prediction();
  else
    predict_every_row();
}

void FastHalfExplicitStepSystem::finish_step()
{
  free_acceleration_ready = false;
  reset_moving_columns();
}
} // namespace pantocat
