#pragma once

#include <pantocat/lac/interleaved_columns.h>
#include <pantocat/lac/local_columns.h>
#include <pantocat/lac/sparse_direct_solver.h>
#include <pantocat/system/semi_discrete_system.h>

#include <string>
#include <vector>

namespace pantocat
{
/**
 * @p S = K + c_D D + c_M M (@p damping_factor c_D, @p mass_factor c_M) of
 * @p system, on its sparsity pattern: the matrix of an implicit step, Sec. 5.2
 * (BDF-2: c_D = c, c_M = c^2).
 */
void assemble_iteration_matrix(const SemiDiscreteSystem& system, double damping_factor,
                               double mass_factor, dealii::SparseMatrix<double>& S);

/**
 * The constant matrix S = K + c_D D + c_M M of an implicit step (BDF-2:
 * c_D = c, c_M = c^2; generalized-alpha: c_D = gamma/(beta h),
 * c_M = (1 - alpha_m)/((1 - alpha_f) beta h^2)), factorised once, with the
 * batches of right-hand sides that the integrators solve with it for the
 * moving constraints (the contacts, whose rows change every step): per moving
 * constraint an S batch (its columns) and an M batch (M^-1 G^T, ...), both
 * LocalColumns (they reach a few dozen rows around the contact), and the
 * base solution, a full vector solved on its own. The
 * constraints with constant rows (droppers, supports) have no batch: their
 * columns are computed once, truncated, by FixedConstraintSchur (or
 * FixedConstraintBlock).
 */
class IterationMatrix
{
public:
  IterationMatrix(const SemiDiscreteSystem& system, double damping_factor,
                  double mass_factor, const std::string& what, LinearSolverType solver);

  SparseDirectSolver inverse;
  std::vector<unsigned int> fixed, moving; ///< constraints with constant / moving rows
  /// position[i]: the index of constraint i in `fixed` or in `moving`.
  std::vector<unsigned int> position;
  std::vector<char> moves; ///< moves[i]: constraint i is in `moving`
  std::vector<LocalColumns> S_columns, M_columns; ///< per moving constraint
  dealii::Vector<double> base;                    ///< the base solution
};
} // namespace pantocat
