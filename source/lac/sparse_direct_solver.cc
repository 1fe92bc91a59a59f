#include <pantocat/base/input_error.h>
#include <pantocat/lac/sparse_direct_solver.h>

namespace pantocat
{
void SparseDirectSolver::factorize(const dealii::SparseMatrix<double>& matrix,
                                   const std::string& what)
{
  try
  {
    umfpack.initialize(matrix);
  }
  catch (const std::exception&)
  {
    throw SimulationError("the " + what + " is singular and cannot be factorised");
  }
}

void SparseDirectSolver::solve(dealii::Vector<double>& x) const
{
  ++solves;
  umfpack.solve(x);
}
} // namespace pantocat
