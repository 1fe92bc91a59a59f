#pragma once

#include <pantocat/constrained/constrained_operator.h>

#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <vector>

namespace pantocat
{
/**
 * The plain ConstrainedOperator, the oracle of the fast one: A assembled and
 * factorised by UMFPACK; a column A^-1 G_i^T by one full solve per constraint
 * (those of constant rows once, those of moving rows at each new time
 * point); the multiplier system of a set J assembled dense, entry by entry
 * as its definition reads, and solved by LAPACK's LU factorisation;
 * A^-1 G^T y by one full solve with G^T y. No truncation, no structure.
 */
class ReferenceConstrainedOperator : public ConstrainedOperator
{
public:
  ReferenceConstrainedOperator(const SemiDiscreteSystem& system,
                               const Definition& definition);

  void set_rows(const std::vector<ConstraintState>& rows, double t) override;
  void apply_inverse(dealii::Vector<double>& x) const override;
  void solve_history(double t, const dealii::Vector<double>& h,
                     const dealii::Vector<double>& r,
                     dealii::Vector<double>& out) override;
  void solve_multipliers(const std::vector<unsigned int>& set, std::vector<double>& y,
                         const char* what) override;
  void add_columns(const std::vector<double>& y, dealii::Vector<double>& x) override;

private:
  /// A^-1 G_i^T for the rows of set_rows().
  const dealii::Vector<double>& column(unsigned int i);

  Definition definition;
  dealii::SparseMatrix<double> A;
  dealii::SparseDirectUMFPACK factor;
  const std::vector<ConstraintState>* rows = nullptr;
  double time = 0.;
  std::vector<dealii::Vector<double>> columns;
  std::vector<char> column_current; ///< columns[i] is that of the rows at `time`
};
} // namespace pantocat
