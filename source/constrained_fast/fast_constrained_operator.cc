#include <pantocat/base/input_error.h>
#include <pantocat/constrained_fast/fast_constrained_operator.h>
#include <pantocat/constrained_fast/iteration_matrix.h>
#include <pantocat/constrained_fast/multiplier_system.h>

#include <algorithm>
#include <array>

namespace pantocat
{
FastConstrainedOperator::FastConstrainedOperator(const SemiDiscreteSystem& system,
                                                 const Definition& d)
    : ConstrainedOperator(system), definition(d)
{
  if (d.mass == 1. && d.damping == 0. && d.stiffness == 0.)
    inverse.initialize(system.mass, system.mass_is_diagonal, d.what, d.solver);
  else
  {
    // Formed as every iteration matrix is (K, then + c_D D, then + c_M M).
    dealii::SparseMatrix<double> A;
    if (d.stiffness == 1.)
      assemble_iteration_matrix(system, d.damping, d.mass, A);
    else
    {
      A.reinit(*system.sparsity);
      A.add(d.stiffness, system.stiffness);
      A.add(d.damping, system.damping);
      A.add(d.mass, system.mass);
    }
    inverse.initialize(A, false, d.what, d.solver);
  }
  partition();
}

void FastConstrainedOperator::partition()
{
  const unsigned int m = system.n_constraints();
  moves.assign(m, 0);
  position.assign(m, 0);
  for (unsigned int i = 0; i < m; ++i)
  {
    moves[i] = system.constraints[i]->depends_on_time();
    auto& list = moves[i] ? moving : fixed;
    position[i] = list.size();
    list.push_back(i);
  }
  columns.resize(moving.size());
  for (LocalColumns& X : columns)
    X.reinit(system.n_dofs());
}

void FastConstrainedOperator::set_rows(const std::vector<ConstraintState>& r,
                                       const double t)
{
  if (rows == &r && time == t)
    return;
  rows = &r;
  time = t;
  columns_current = false;
}

void FastConstrainedOperator::initialize_fixed()
{
  std::vector<const SparseRow*> G;
  std::vector<double> C;
  CompressedRows fixed_G;
  for (const unsigned int i : fixed)
  {
    const ConstraintState& r = (*rows)[i];
    if (r.G_t.size() > 0 || r.G_tt.size() > 0)
      throw SimulationError("constraint " + system.constraints[i]->name() +
                            " has constant rows but a time derivative");
    G.push_back(&r.G);
    C.push_back(compliance(i));
    fixed_G.push_back(r.G);
  }
  schur.initialize(
      G, inverse, system.n_dofs(),
      "matrix G A^-1 G^T + C of the fixed constraints, A the " + definition.what, C);
  fixed_at_row.build(fixed_G, system.n_dofs());
  keep.assign(fixed.size(), false);
  factors.assign(fixed.size(), 0.);
  seen.assign(fixed.size(), 0);
  fixed_ready = true;
}

void FastConstrainedOperator::update_moving_columns()
{
  if (!fixed_ready)
    initialize_fixed();
  if (columns_current)
    return;
  for (unsigned int c = 0; c < moving.size(); ++c)
  {
    const ConstraintState& r = (*rows)[moving[c]];
    LocalColumns& X = columns[c];
    X.clear();
    X.add_row(0, r.G, 1.);
    if (rate_weight(moving[c]) != 0.)
      X.add_row(1, r.G_t, 1.);
    inverse.apply(X);
  }
  columns_current = true;
}

void FastConstrainedOperator::apply_inverse(dealii::Vector<double>& v) const
{
  inverse.apply(v);
}

void FastConstrainedOperator::solve_history(const double t,
                                            const dealii::Vector<double>& h,
                                            const dealii::Vector<double>& r,
                                            dealii::Vector<double>& out)
{
  const SparseDirectSolver* factor = inverse.factorised();
  const bool split = factor && definition.stiffness != 0.;
  if (!operators)
    operators = split
                    ? std::make_unique<PatternOperators>(
                          system,
                          PatternOperators::IterationFactors{
                              definition.mass, definition.damping, definition.stiffness})
                    : std::make_unique<PatternOperators>(system);
  operators->set_time(t);
  out.reinit(system.n_dofs(), true);
  if (!split)
  {
    operators->history(h, r, out);
    inverse.apply(out);
    return;
  }
  // The damping split: A^-1 (f + M (h + mu r) + E r) + gamma r.
  shifted.reinit(system.n_dofs(), true);
  for (const PatternOperators::Shift& b : operators->shifts())
  {
    double* __restrict s = shifted.begin();
    const double* __restrict hi = h.begin();
    const double* __restrict ri = r.begin();
    for (unsigned int i = b.first; i < b.last; ++i)
      s[i] = hi[i] + b.mu * ri[i];
  }
  operators->solve_history(shifted, r, *factor, out);
}

void FastConstrainedOperator::fill_border(const unsigned int c, const unsigned int i)
{
  const LocalColumns& X = columns[position[i]];
  const double e = rate_weight(i);
  // Fixed row k, column c: G_k A^-1 G_c^T. Row c, fixed column k:
  // (G_c + e G_t,c) A^-1 G_k^T = G_k A^-1 (G_c + e G_t,c)^T (A symmetric).
  // Both +0, as reinit() left them, where the columns do not reach row k.
  fixed_at_row.rows_in(X.reach(), reached, seen);
  for (const unsigned int k : reached)
  {
    if (!keep[k])
      continue;
    const SparseRow& G_k = (*rows)[fixed[k]].G;
    if (e == 0.)
      Bc[c](k) = Cr[c](k) = X.dot(G_k, 0);
    else
    {
      const std::array<double, LocalColumns::width> GX = X.dots(G_k);
      Bc[c](k) = GX[0];
      Cr[c](k) = Bc[c](k) + e * GX[1];
    }
  }
  for (unsigned int r = 0; r < moving_in.size(); ++r)
  {
    const unsigned int j = moving_in[r];
    const double e_j = rate_weight(j);
    D(r, c) = X.dot((*rows)[j].G, 0);
    if (e_j != 0.)
      D(r, c) += e_j * X.dot((*rows)[j].G_t, 0);
  }
  D(c, c) += compliance(i);
}

void FastConstrainedOperator::solve_multipliers(const std::vector<unsigned int>& set,
                                                std::vector<double>& y, const char* what)
{
  update_moving_columns();
  std::fill(keep.begin(), keep.end(), false);
  moving_in.clear();
  for (const unsigned int i : set)
    if (moves[i])
      moving_in.push_back(i);
    else
      keep[position[i]] = true;
  schur.select(keep);
  const unsigned int mF = fixed.size(), p = moving_in.size();
  x.reinit(mF);
  z.reinit(p);
  for (auto* border : {&Bc, &Cr})
  {
    border->resize(p);
    for (dealii::Vector<double>& column : *border)
      column.reinit(mF);
  }
  D.reinit(p, p);
  for (unsigned int k = 0; k < mF; ++k)
    if (keep[k])
      x(k) = y[fixed[k]];
  for (unsigned int c = 0; c < p; ++c)
  {
    fill_border(c, moving_in[c]);
    z(c) = y[moving_in[c]];
  }
  solve_bordered([&](const auto& xs) { schur.solve(xs); }, Bc, Cr, D, x, z, rhs, batch,
                 time, what);
  y.assign(system.n_constraints(), 0.);
  for (unsigned int k = 0; k < mF; ++k)
    if (keep[k])
      y[fixed[k]] = x(k);
  for (unsigned int c = 0; c < p; ++c)
    y[moving_in[c]] = z(c);
}

void FastConstrainedOperator::add_columns(const std::vector<double>& y,
                                          dealii::Vector<double>& v)
{
  update_moving_columns();
  bool any = false;
  for (unsigned int k = 0; k < fixed.size(); ++k)
  {
    factors[k] = y[fixed[k]];
    any = any || factors[k] != 0.;
  }
  if (any)
    schur.add_columns(factors, v);
  for (unsigned int c = 0; c < moving.size(); ++c)
    if (const double y_c = y[moving[c]]; y_c != 0.)
      columns[c].add_combination({{y_c, 0., 0., 0.}}, v);
}
} // namespace pantocat
