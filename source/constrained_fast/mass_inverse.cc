#include <pantocat/base/input_error.h>
#include <pantocat/constrained_fast/mass_inverse.h>

#include <algorithm>

namespace pantocat
{
namespace
{
/// Rows of @p matrix with a non-zero off-diagonal entry.
std::vector<unsigned int> rows_with_coupling(const dealii::SparseMatrix<double>& matrix)
{
  std::vector<unsigned int> rows;
  for (unsigned int i = 0; i < matrix.m(); ++i)
    for (auto it = matrix.begin(i); it != matrix.end(i); ++it)
      if (it->column() != i && it->value() != 0.)
      {
        rows.push_back(i);
        break;
      }
  return rows;
}
} // namespace

void MassInverse::initialize(const dealii::SparseMatrix<double>& matrix,
                             const bool is_diagonal, const std::string& what,
                             const LinearSolverType solver)
{
  coupled_rows = is_diagonal ? std::vector<unsigned int>() : rows_with_coupling(matrix);
  // A small coupled block (a lumped pantograph) beside a diagonal rest.
  bool block_closed = coupled_rows.size() <= 16;
  for (const unsigned int i : coupled_rows)
    for (auto it = matrix.begin(i); block_closed && it != matrix.end(i); ++it)
      block_closed =
          it->value() == 0. ||
          std::binary_search(coupled_rows.begin(), coupled_rows.end(), it->column());
  diagonal = block_closed;
  if (!diagonal)
  {
    coupled_rows.clear();
    factorization.factorize(matrix, what, solver);
    return;
  }
  inverse_diagonal.reinit(matrix.m());
  for (unsigned int i = 0; i < matrix.m(); ++i)
  {
    if (std::binary_search(coupled_rows.begin(), coupled_rows.end(), i))
      continue;
    const double d = matrix.diag_element(i);
    if (!(d > 0.))
      throw SimulationError("the " + what + " has a non-positive diagonal entry " +
                            std::to_string(d) + " at unknown " + std::to_string(i));
    inverse_diagonal(i) = 1. / d;
  }
  scaling = inverse_diagonal;
  for (const unsigned int i : coupled_rows)
    scaling(i) = 1.;
  const unsigned int c = coupled_rows.size();
  coupled_inverse.reinit(c, c);
  for (unsigned int k = 0; k < c; ++k)
    for (unsigned int l = 0; l < c; ++l)
      coupled_inverse(k, l) = matrix.el(coupled_rows[k], coupled_rows[l]);
  if (c > 0)
    coupled_inverse.gauss_jordan();
  block_in.reinit(c);
  block_out.reinit(c);
}

void MassInverse::apply(dealii::Vector<double>& x) const
{
  if (!diagonal)
  {
    factorization.solve(x);
    return;
  }
  const unsigned int c = coupled_rows.size();
  for (unsigned int k = 0; k < c; ++k)
    block_in(k) = x(coupled_rows[k]);
  double* __restrict y = x.begin();
  const double* __restrict d = inverse_diagonal.begin();
  for (unsigned int i = 0, n = x.size(); i < n; ++i)
    y[i] *= d[i];
  if (c == 0)
    return;
  coupled_inverse.vmult(block_out, block_in);
  for (unsigned int k = 0; k < c; ++k)
    x(coupled_rows[k]) = block_out(k);
}

namespace
{
/**
 * The diagonal forms of MassInverse on four interleaved columns @p X: every
 * row scaled (@p scale_rows, 0 on the coupled rows), then the coupled rows
 * = the block's inverse times their values before (@p store(i, r, value)).
 */
template <typename Columns, typename ScaleRows, typename Store>
void scale_and_solve_block(const std::vector<unsigned int>& coupled_rows,
                           const dealii::FullMatrix<double>& block_inverse,
                           const Columns& X, const ScaleRows& scale_rows,
                           const Store& store)
{
  const unsigned int c = coupled_rows.size(), w = InterleavedColumns::width;
  std::vector<double> coupled(c * w);
  for (unsigned int k = 0; k < c; ++k)
    for (unsigned int r = 0; r < w; ++r)
      coupled[k * w + r] = X(coupled_rows[k], r);
  scale_rows();
  for (unsigned int k = 0; k < c; ++k)
    for (unsigned int r = 0; r < w; ++r)
    {
      double s = 0.;
      for (unsigned int l = 0; l < c; ++l)
        s += block_inverse(k, l) * coupled[l * w + r];
      store(coupled_rows[k], r, s);
    }
}
} // namespace

void MassInverse::apply(InterleavedColumns& X) const
{
  if (!diagonal)
  {
    factorization.solve_interleaved(X.data(), InterleavedColumns::width);
    return;
  }
  constexpr unsigned int w = InterleavedColumns::width;
  const auto scale_rows = [&]()
  {
    double* __restrict y = X.data();
    const double* __restrict d = inverse_diagonal.begin();
    for (unsigned int i = 0, n = X.size(); i < n; ++i)
      for (unsigned int r = 0; r < w; ++r)
        y[i * w + r] *= d[i];
  };
  scale_and_solve_block(coupled_rows, coupled_inverse, X, scale_rows,
                        [&](const unsigned int i, const unsigned int r,
                            const double value) { X(i, r) = value; });
}

void MassInverse::apply(LocalColumns& X) const
{
  if (!diagonal)
  {
    X.solve(factorization);
    return;
  }
  scale_and_solve_block(
      coupled_rows, coupled_inverse, X, [&]() { X.scale_rows(inverse_diagonal); },
      [&](const unsigned int i, const unsigned int r, const double value)
      { X.set(i, r, value); });
}

void MassInverse::apply_coupled_rows(dealii::Vector<double>& x) const
{
  const unsigned int c = coupled_rows.size();
  if (c == 0)
    return;
  for (unsigned int k = 0; k < c; ++k)
    block_in(k) = x(coupled_rows[k]);
  coupled_inverse.vmult(block_out, block_in);
  for (unsigned int k = 0; k < c; ++k)
    x(coupled_rows[k]) = block_out(k);
}

void MassInverse::apply_block_to_row(const SparseRow& row,
                                     dealii::Vector<double>& column) const
{
  const unsigned int c = coupled_rows.size();
  if (c == 0)
    return;
  block_in = 0.;
  for (std::size_t m = 0; m < row.size(); ++m)
  {
    const auto it =
        std::lower_bound(coupled_rows.begin(), coupled_rows.end(), row.index[m]);
    if (it != coupled_rows.end() && *it == row.index[m])
      block_in(it - coupled_rows.begin()) += row.value[m];
  }
  coupled_inverse.vmult(block_out, block_in);
  for (unsigned int k = 0; k < c; ++k)
    column(coupled_rows[k]) = block_out(k);
}

void MassInverse::apply_to_row(const SparseRow& row, dealii::Vector<double>& column) const
{
  if (diagonal)
  {
    for (std::size_t k = 0; k < row.size(); ++k)
      column[row.index[k]] += row.value[k] * inverse_diagonal[row.index[k]];
    apply_block_to_row(row, column);
    return;
  }
  column = 0.;
  row.add_transpose_to(column, 1.);
  factorization.solve(column);
}

void MassInverse::reset_column(const SparseRow& row, dealii::Vector<double>& column) const
{
  if (!diagonal)
  {
    column = 0.;
    return;
  }
  for (const unsigned int i : row.index)
    column[i] = 0.;
  for (const unsigned int i : coupled_rows)
    column[i] = 0.;
}

void MassInverse::add_column(const SparseRow& row, const dealii::Vector<double>& column,
                             const double factor, dealii::Vector<double>& y) const
{
  if (!diagonal)
  {
    y.add(factor, column);
    return;
  }
  // The pattern of the row, then the coupled rows not in it.
  for (const unsigned int i : row.index)
    y[i] += factor * column[i];
  for (const unsigned int i : coupled_rows)
    if (std::find(row.index.begin(), row.index.end(), i) == row.index.end())
      y[i] += factor * column[i];
}

void MassInverse::add_rows(const std::vector<RowTerm>& terms,
                           dealii::Vector<double>& y) const
{
  if (terms.empty())
    return;
  if (!diagonal)
  {
    work.reinit(y.size()); // zero
    for (const auto& [row, factor] : terms)
      row->add_transpose_to(work, factor);
    factorization.solve(work);
    y += work;
    return;
  }
  const unsigned int c = coupled_rows.size();
  if (c > 0)
    block_in = 0.;
  for (const auto& [row, factor] : terms)
    for (std::size_t k = 0; k < row->size(); ++k)
    {
      const unsigned int i = row->index[k];
      y[i] += factor * row->value[k] * inverse_diagonal[i]; // 0 on coupled rows
      if (c == 0)
        continue;
      const auto it = std::lower_bound(coupled_rows.begin(), coupled_rows.end(), i);
      if (it != coupled_rows.end() && *it == i)
        block_in(it - coupled_rows.begin()) += factor * row->value[k];
    }
  if (c == 0)
    return;
  coupled_inverse.vmult(block_out, block_in);
  for (unsigned int k = 0; k < c; ++k)
    y(coupled_rows[k]) += block_out(k);
}
} // namespace pantocat
