#pragma once

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <memory>
#include <string>

namespace pantocat
{
/**
 * The semi-discrete operators of one body on its free unknowns:
 *   M a + D v + K q = load,
 * e.g. (29) for the carrier (K = S_c) and (30) for the contact wire
 * (K = S_w + K_w), before the constraint forces are added. The Dirichlet
 * unknowns of (3) are eliminated.
 */
struct BlockOperator
{
  std::string name;
  std::unique_ptr<dealii::SparsityPattern> sparsity =
      std::make_unique<dealii::SparsityPattern>();
  dealii::SparseMatrix<double> mass;
  dealii::SparseMatrix<double> damping;
  dealii::SparseMatrix<double> stiffness;
  dealii::Vector<double> load;
  bool mass_is_diagonal = false;
  /// False if K of this body alone is singular and only its constraints hold
  /// it (a stitch wire, clamped to the carrier at its ends).
  bool stiffness_is_definite = true;

  unsigned int size() const { return load.size(); }

  /// Reinitialise the matrices on a finished sparsity pattern with @p n unknowns.
  void reinit_matrices(unsigned int n)
  {
    mass.reinit(*sparsity);
    damping.reinit(*sparsity);
    stiffness.reinit(*sparsity);
    load.reinit(n);
  }
};
} // namespace pantocat
