#include <pantocat/base/input_error.h>
#include <pantocat/constrained_fast/fixed_constraint_schur.h>
#include <pantocat/constrained_fast/truncated_columns.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace pantocat
{
namespace
{
struct Entry
{
  unsigned int row, column;
  double value;
};

/**
 * The entries S_kl = G_k A^-1 G_l^T with k >= l that are not zero, S_kk, and
 * the columns A^-1 G_l^T truncated.
 */
std::vector<Entry> lower_entries(const std::vector<const SparseRow*>& rows,
                                 const FixedConstraintSchur::ColumnSolver& A,
                                 const unsigned int n_dofs, std::vector<double>& diagonal,
                                 std::vector<SparseRow>& columns)
{
  const unsigned int m = rows.size();
  std::vector<Entry> lower;
  diagonal.assign(m, 0.);
  dealii::Vector<double> column(n_dofs);
  for (unsigned int l = 0; l < m; ++l)
  {
    A.apply(*rows[l], column);
    columns.push_back(truncated(column));
    for (unsigned int k = l; k < m; ++k)
    {
      const double s = rows[k]->dot(column);
      if (k == l)
        diagonal[l] = s;
      else if (s != 0.)
        lower.push_back({k, l, s});
    }
    A.reset(*rows[l], column);
  }
  return lower;
}
/// y += w, then w = 0, in one pass.
void add_and_clear(dealii::Vector<double>& w, dealii::Vector<double>& y)
{
  double* __restrict wi = w.begin();
  double* __restrict yi = y.begin();
  for (unsigned int i = 0; i < w.size(); ++i)
  {
    yi[i] += wi[i];
    wi[i] = 0.;
  }
}
} // namespace

FixedConstraintSchur::ColumnSolver
FixedConstraintSchur::column_solver(const MassInverse& A, const bool keep_columns)
{
  ColumnSolver s;
  s.apply = [&A](const SparseRow& row, dealii::Vector<double>& column)
  { A.apply_to_row(row, column); };
  s.reset = [&A](const SparseRow& row, dealii::Vector<double>& column)
  { A.reset_column(row, column); };
  s.solve = [&A](dealii::Vector<double>& x) { A.apply(x); };
  s.solve_columns = [&A](InterleavedColumns& X) { A.apply(X); };
  const SparseDirectSolver* factor = A.factorised();
  // A (block-)diagonal A: columns on the rows' pattern, always cheaper.
  s.solve_cost = factor ? factor->solve_cost() : 1e300;
  s.keep_columns = keep_columns;
  s.solve_one_at_a_time = factor && factor->has_twisted_blocks();
  return s;
}

FixedConstraintSchur::ColumnSolver
FixedConstraintSchur::column_solver(const SparseDirectSolver& A, const bool keep_columns)
{
  ColumnSolver s;
  s.apply = [&A](const SparseRow& row, dealii::Vector<double>& column)
  {
    row.add_transpose_to(column, 1.);
    A.solve(column);
  };
  s.reset = [](const SparseRow&, dealii::Vector<double>& column) { column = 0.; };
  s.solve = [&A](dealii::Vector<double>& x) { A.solve(x); };
  s.solve_columns = [&A](InterleavedColumns& X)
  { A.solve_interleaved(X.data(), InterleavedColumns::width); };
  s.solve_cost = A.solve_cost();
  s.keep_columns = keep_columns;
  s.solve_one_at_a_time = A.has_twisted_blocks();
  return s;
}

void FixedConstraintSchur::initialize(const std::vector<const SparseRow*>& rows,
                                      const MassInverse& A, const unsigned int n_dofs,
                                      const std::string& name,
                                      const std::vector<double>& C)
{
  initialize(rows, column_solver(A), n_dofs, name, C);
}

void FixedConstraintSchur::initialize(const std::vector<const SparseRow*>& rows,
                                      const SparseDirectSolver& A,
                                      const unsigned int n_dofs, const std::string& name,
                                      const std::vector<double>& C)
{
  initialize(rows, column_solver(A), n_dofs, name, C);
}

void FixedConstraintSchur::initialize(const std::vector<const SparseRow*>& G,
                                      const ColumnSolver& A, const unsigned int n_dofs,
                                      const std::string& name,
                                      const std::vector<double>& C)
{
  n = G.size();
  what = name;
  compliance = C.empty() ? std::vector<double>(n, 0.) : C;
  if (compliance.size() != n)
    throw SimulationError("the " + what + " got " + std::to_string(C.size()) +
                          " compliances for " + std::to_string(n) + " constraints");
  selected.clear();
  factorised = false;
  if (n == 0)
    return;
  columns.clear();
  std::vector<Entry> lower = lower_entries(G, A, n_dofs, diagonal, columns);
  column_runs.initialize(columns, n_dofs);
  rows.clear();
  if (!A.keep_columns && static_cast<double>(n_column_entries()) > A.solve_cost &&
      A.solve)
  {
    // One solve with G_F^T lambda reads fewer entries than the columns.
    column_runs.clear();
    for (const SparseRow* g : G)
      rows.push_back(*g);
    solve_with_A = A.solve;
    solve_columns_with_A = A.solve_columns;
    solve_one_at_a_time = A.solve_one_at_a_time;
    work.reinit(n_dofs);
    work_pair.reinit(n_dofs);
  }
  // add_columns() reads the runs; the rows are kept only when asked for.
  if (!A.keep_columns)
    columns = {};
  for (unsigned int k = 0; k < n; ++k)
    if (!(diagonal[k] > 0.))
      throw SimulationError("the " + what +
                            " has a non-positive diagonal entry at "
                            "constraint " +
                            std::to_string(k) + " (a constraint row without unknowns?)");
  // Drop what A^-1's decay has made round-off.
  std::vector<Entry> kept;
  for (const Entry& e : lower)
    if (std::abs(e.value) > 1e-15 * std::sqrt(diagonal[e.row] * diagonal[e.column]))
      kept.push_back(e);

  diagonal_only = kept.empty();
  dealii::DynamicSparsityPattern graph(n, n);
  for (unsigned int k = 0; k < n; ++k)
    graph.add(k, k);
  for (const Entry& e : kept)
  {
    graph.add(e.row, e.column);
    graph.add(e.column, e.row);
  }
  std::vector<dealii::types::global_dof_index> order(n);
  dealii::SparsityTools::reorder_Cuthill_McKee(graph, order);
  new_index.assign(order.begin(), order.end());

  dealii::DynamicSparsityPattern permuted_graph(n, n);
  for (unsigned int k = 0; k < n; ++k)
    permuted_graph.add(new_index[k], new_index[k]);
  for (const Entry& e : kept)
  {
    permuted_graph.add(new_index[e.row], new_index[e.column]);
    permuted_graph.add(new_index[e.column], new_index[e.row]);
  }
  pattern.copy_from(permuted_graph);
  entries.reinit(pattern);
  selected_matrix.reinit(pattern);
  for (unsigned int k = 0; k < n; ++k)
    entries.set(new_index[k], new_index[k], diagonal[k]);
  for (const Entry& e : kept)
  {
    entries.set(new_index[e.row], new_index[e.column], e.value);
    entries.set(new_index[e.column], new_index[e.row], e.value);
  }
  permuted.reinit(n);
  // The same entries by original row, for vmult().
  std::vector<unsigned int> old_index(n);
  for (unsigned int k = 0; k < n; ++k)
    old_index[new_index[k]] = k;
  row_start.assign(1, 0);
  row_column.clear();
  row_value.clear();
  row_coupling.clear();
  for (unsigned int k = 0; k < n; ++k)
  {
    const unsigned int i = new_index[k];
    for (auto it = entries.begin(i); it != entries.end(i); ++it)
    {
      const unsigned int l = old_index[it->column()];
      row_column.push_back(l);
      row_value.push_back(it->value());
      row_coupling.push_back(std::abs(it->value()) /
                             std::sqrt(diagonal[k] * diagonal[l]));
    }
    row_start.push_back(row_column.size());
  }
}

void FixedConstraintSchur::select(const std::vector<bool>& keep)
{
  if (n == 0 || (factorised &&
                 std::equal(keep.begin(), keep.end(), selected.begin(), selected.end())))
    return;
  selected.assign(keep.begin(), keep.end());
  factorised = true;
  if (diagonal_only)
  {
    inverse_diagonal.resize(n);
    for (unsigned int k = 0; k < n; ++k)
      inverse_diagonal[k] = keep[k] ? 1. / (diagonal[k] + compliance[k]) : 0.;
    return;
  }
  std::vector<bool> kept_new(n);
  std::vector<double> compliance_new(n);
  for (unsigned int k = 0; k < n; ++k)
  {
    kept_new[new_index[k]] = keep[k];
    compliance_new[new_index[k]] = compliance[k];
  }
  for (unsigned int i = 0; i < n; ++i)
    for (auto it = entries.begin(i), s = selected_matrix.begin(i); it != entries.end(i);
         ++it, ++s)
    {
      const unsigned int j = it->column();
      s->value() = kept_new[i] && kept_new[j]
                       ? it->value() + (i == j ? compliance_new[i] : 0.)
                       : (i == j ? 1. : 0.); // identity
    }
  // Cuthill-McKee keeps the band narrow; a consistent FEM mass makes it a few
  // dozen constraints wide (M^-1 decays slowly), still far cheaper banded.
  factor.factorize(selected_matrix, what, LinearSolverType::banded, 96);
}

void FixedConstraintSchur::add_columns(const std::vector<double>& factors,
                                       dealii::Vector<double>& y) const
{
  if (!rows.empty())
  {
    bool any = false;
    for (unsigned int k = 0; k < n; ++k)
      if (factors[k] != 0.)
      {
        rows[k].add_transpose_to(work, factors[k]);
        any = true;
      }
    if (!any)
      return;
    solve_with_A(work);
    add_and_clear(work, y);
    return;
  }
  column_runs.add(factors.data(), nullptr, y.begin(), nullptr);
}

void FixedConstraintSchur::add_columns(const std::vector<double>& f,
                                       dealii::Vector<double>& y,
                                       const std::vector<double>& g,
                                       dealii::Vector<double>& z) const
{
  if (!rows.empty())
  {
    if (!solve_columns_with_A || solve_one_at_a_time)
    {
      add_columns(f, y);
      add_columns(g, z);
      return;
    }
    // G_F^T f and G_F^T g solved side by side: one sweep instead of two.
    // (A factor with twisted blocks solves them one at a time, above: each
    // twisted solve takes about half the time of the plain sweep of two.)
    bool any = false;
    for (unsigned int k = 0; k < n; ++k)
    {
      if (f[k] != 0.)
        work_pair.add_row(0, rows[k], f[k]);
      if (g[k] != 0.)
        work_pair.add_row(1, rows[k], g[k]);
      any = any || f[k] != 0. || g[k] != 0.;
    }
    if (!any)
      return;
    solve_columns_with_A(work_pair);
    work_pair.add_combination({{1., 0., 0., 0.}}, y);
    work_pair.add_combination({{0., 1., 0., 0.}}, z);
    work_pair.clear();
    return;
  }
  column_runs.add(f.data(), g.data(), y.begin(), z.begin());
}

void FixedConstraintSchur::vmult(dealii::Vector<double>& out,
                                 const dealii::Vector<double>& in) const
{
  for (unsigned int k = 0; k < n; ++k)
    out[k] = row_product(k, in.begin());
}

void FixedConstraintSchur::reach_from(const std::vector<unsigned int>& sources,
                                      const std::vector<bool>& among,
                                      const double epsilon,
                                      std::vector<bool>& reached) const
{
  reach_weight.resize(n, 0.);
  reach_queue.clear();
  for (const unsigned int k : sources)
    if (among[k] && reach_weight[k] < 1.)
    {
      reach_weight[k] = 1.;
      reach_touched.push_back(k);
      reach_queue.emplace_back(1., k);
    }
  // Best first (std::push_heap keeps the largest product on top): a
  // constraint leaves the queue with its largest product, and is walked from
  // once with it.
  std::make_heap(reach_queue.begin(), reach_queue.end());
  while (!reach_queue.empty())
  {
    std::pop_heap(reach_queue.begin(), reach_queue.end());
    const auto [weight, k] = reach_queue.back();
    reach_queue.pop_back();
    if (weight < reach_weight[k])
      continue; // a better path came first
    for (unsigned int e = row_start[k]; e < row_start[k + 1]; ++e)
    {
      const unsigned int l = row_column[e];
      const double w = weight * row_coupling[e];
      if (l == k || !among[l] || w <= epsilon || w <= reach_weight[l])
        continue;
      if (reach_weight[l] == 0.)
        reach_touched.push_back(l);
      reach_weight[l] = w;
      reach_queue.emplace_back(w, l);
      std::push_heap(reach_queue.begin(), reach_queue.end());
    }
  }
  for (const unsigned int k : reach_touched)
  {
    reached[k] = true;
    reach_weight[k] = 0.;
  }
  reach_touched.clear();
}

void FixedConstraintSchur::factorize_subset(const std::vector<unsigned int>& subset,
                                            SubsetFactor& out) const
{
  const unsigned int r = subset.size();
  subset_slot.resize(n, -1);
  for (unsigned int l = 0; l < r; ++l)
    subset_slot[subset[l]] = l;
  out.matrix.reinit(r, r);
  for (unsigned int l = 0; l < r; ++l)
  {
    const unsigned int k = subset[l];
    for (unsigned int e = row_start[k]; e < row_start[k + 1]; ++e)
      if (subset_slot[row_column[e]] >= 0)
        out.matrix(l, subset_slot[row_column[e]]) = row_value[e];
    if (!compliance.empty())
      out.matrix(l, l) += compliance[k];
  }
  for (const unsigned int k : subset)
    subset_slot[k] = -1;
  out.rhs.reinit(r, true);
  out.solution.reinit(r, true);
  if (r == 0)
    return;
  out.factor.cholesky(out.matrix);
  out.factor_transposed.copy_transposed(out.factor);
}

void FixedConstraintSchur::SubsetFactor::solve(double* x) const
{
  std::copy(x, x + rhs.size(), rhs.begin());
  factor.forward(solution, rhs);             // L y = x
  factor_transposed.backward(rhs, solution); // L^T z = y
  std::copy(rhs.begin(), rhs.end(), x);
}

std::size_t FixedConstraintSchur::n_column_entries() const
{
  return column_runs.n_entries();
}

void FixedConstraintSchur::solve(dealii::Vector<double>& x) const
{
  if (n == 0)
    return;
  if (diagonal_only)
  {
    double* __restrict y = x.begin();
    const double* __restrict d = inverse_diagonal.data();
    for (unsigned int k = 0; k < n; ++k)
      y[k] *= d[k];
    return;
  }
  const char* __restrict kept = selected.data();
  const unsigned int* __restrict to = new_index.data();
  double* __restrict y = x.begin();
  double* __restrict w = permuted.begin();
  for (unsigned int k = 0; k < n; ++k)
    w[to[k]] = kept[k] ? y[k] : 0.;
  factor.solve(permuted);
  for (unsigned int k = 0; k < n; ++k)
    y[k] = kept[k] ? w[to[k]] : 0.;
}

void FixedConstraintSchur::solve(const std::vector<dealii::Vector<double>*>& xs) const
{
  if (n == 0)
    return;
  if (diagonal_only)
  {
    for (dealii::Vector<double>* x : xs)
      solve(*x);
    return;
  }
  constexpr std::size_t width = 4;
  const char* __restrict kept = selected.data();
  const unsigned int* __restrict to = new_index.data();
  for (std::size_t first = 0; first < xs.size(); first += width)
  {
    const unsigned int k = std::min(width, xs.size() - first);
    interleaved.resize(static_cast<std::size_t>(n) * k);
    double* __restrict w = interleaved.data();
    std::array<double*, width> x{};
    for (unsigned int r = 0; r < k; ++r)
      x[r] = xs[first + r]->begin();
    for (unsigned int i = 0; i < n; ++i)
    {
      double* __restrict wi = w + static_cast<std::size_t>(to[i]) * k;
      for (unsigned int r = 0; r < k; ++r)
        wi[r] = kept[i] ? x[r][i] : 0.;
    }
    factor.solve_interleaved(w, k);
    for (unsigned int i = 0; i < n; ++i)
    {
      const double* __restrict wi = w + static_cast<std::size_t>(to[i]) * k;
      for (unsigned int r = 0; r < k; ++r)
        x[r][i] = kept[i] ? wi[r] : 0.;
    }
  }
}
} // namespace pantocat
