#include <pantocat/base/input_error.h>
#include <pantocat/time/mass_inverse.h>

namespace pantocat
{
void MassInverse::initialize(const dealii::SparseMatrix<double>& matrix,
                             const bool is_diagonal, const std::string& what)
{
  diagonal = is_diagonal;
  if (!diagonal)
  {
    factorization.factorize(matrix, what);
    return;
  }
  inverse_diagonal.reinit(matrix.m());
  for (unsigned int i = 0; i < matrix.m(); ++i)
  {
    const double d = matrix.diag_element(i);
    if (!(d > 0.))
      throw SimulationError("the " + what + " has a non-positive diagonal entry " +
                            std::to_string(d) + " at unknown " + std::to_string(i));
    inverse_diagonal(i) = 1. / d;
  }
}

void MassInverse::apply(dealii::Vector<double>& x) const
{
  if (diagonal)
    x.scale(inverse_diagonal);
  else
    factorization.solve(x);
}

void MassInverse::apply_to_row(const SparseRow& row, dealii::Vector<double>& column) const
{
  if (diagonal)
  {
    for (std::size_t k = 0; k < row.size(); ++k)
      column[row.index[k]] += row.value[k] * inverse_diagonal[row.index[k]];
    return;
  }
  column = 0.;
  row.add_transpose_to(column, 1.);
  factorization.solve(column);
}

void MassInverse::reset_column(const SparseRow& row, dealii::Vector<double>& column) const
{
  if (diagonal)
    for (const unsigned int i : row.index)
      column[i] = 0.;
  else
    column = 0.;
}

void MassInverse::add_column(const SparseRow& row, const dealii::Vector<double>& column,
                             const double factor, dealii::Vector<double>& y) const
{
  if (!diagonal)
  {
    y.add(factor, column);
    return;
  }
  for (const unsigned int i : row.index)
    y[i] += factor * column[i];
}
} // namespace pantocat
