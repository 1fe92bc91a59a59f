#include <pantocat/base/input_error.h>
#include <pantocat/time/fixed_constraint_schur.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>

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

/// The entries of @p column above 1e-16 of its largest one.
SparseRow truncated(const dealii::Vector<double>& column)
{
  const double tolerance = 1e-16 * column.linfty_norm();
  SparseRow row;
  for (unsigned int i = 0; i < column.size(); ++i)
    if (std::abs(column[i]) > tolerance)
      row.add(i, column[i]);
  return row;
}

/**
 * The entries S_kl = G_k A^-1 G_l^T with k >= l that are not zero, S_kk, and
 * the columns A^-1 G_l^T truncated.
 */
std::vector<Entry> lower_entries(const std::vector<const SparseRow*>& rows,
                                 const MassInverse& A, const unsigned int n_dofs,
                                 std::vector<double>& diagonal,
                                 std::vector<SparseRow>& columns)
{
  const unsigned int m = rows.size();
  std::vector<Entry> lower;
  diagonal.assign(m, 0.);
  dealii::Vector<double> column(n_dofs);
  for (unsigned int l = 0; l < m; ++l)
  {
    A.apply_to_row(*rows[l], column);
    columns.push_back(truncated(column));
    for (unsigned int k = l; k < m; ++k)
    {
      const double s = rows[k]->dot(column);
      if (k == l)
        diagonal[l] = s;
      else if (s != 0.)
        lower.push_back({k, l, s});
    }
    A.reset_column(*rows[l], column);
  }
  return lower;
}
} // namespace

void FixedConstraintSchur::initialize(const std::vector<const SparseRow*>& rows,
                                      const MassInverse& A, const unsigned int n_dofs,
                                      const std::string& name)
{
  n = rows.size();
  what = name;
  selected.clear();
  factorised = false;
  if (n == 0)
    return;
  std::vector<double> diagonal;
  columns.clear();
  std::vector<Entry> lower = lower_entries(rows, A, n_dofs, diagonal, columns);
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
}

void FixedConstraintSchur::select(const std::vector<bool>& keep)
{
  if (n == 0 || (factorised && keep == selected))
    return;
  selected = keep;
  std::vector<bool> kept_new(n);
  for (unsigned int k = 0; k < n; ++k)
    kept_new[new_index[k]] = keep[k];
  for (unsigned int i = 0; i < n; ++i)
    for (auto it = entries.begin(i), s = selected_matrix.begin(i); it != entries.end(i);
         ++it, ++s)
    {
      const unsigned int j = it->column();
      s->value() =
          kept_new[i] && kept_new[j] ? it->value() : (i == j ? 1. : 0.); // identity
    }
  factor.factorize(selected_matrix, what);
  factorised = true;
}

void FixedConstraintSchur::add_columns(const std::vector<double>& factors,
                                       dealii::Vector<double>& y) const
{
  for (unsigned int k = 0; k < n; ++k)
    if (factors[k] != 0.)
      columns[k].add_transpose_to(y, factors[k]);
}

std::size_t FixedConstraintSchur::n_column_entries() const
{
  std::size_t s = 0;
  for (const SparseRow& c : columns)
    s += c.size();
  return s;
}

void FixedConstraintSchur::solve(dealii::Vector<double>& x) const
{
  if (n == 0)
    return;
  for (unsigned int k = 0; k < n; ++k)
    permuted[new_index[k]] = selected[k] ? x[k] : 0.;
  factor.solve(permuted);
  for (unsigned int k = 0; k < n; ++k)
    x[k] = selected[k] ? permuted[new_index[k]] : 0.;
}
} // namespace pantocat
