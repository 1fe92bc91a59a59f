#pragma once

#include <pantocat/constrained/constrained_operator.h>
#include <pantocat/constrained_fast/fixed_constraint_schur.h>
#include <pantocat/constrained_fast/mass_inverse.h>
#include <pantocat/lac/local_columns.h>
#include <pantocat/lac/sparse_row.h>
#include <pantocat/system/pattern_operators.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <memory>
#include <vector>

namespace pantocat
{
/**
 * The structured ConstrainedOperator, O(n + m) per step:
 *
 *  - A^-1 by MassInverse (a scaling for a (block-)diagonal A, else the
 *    banded Cholesky factor of SparseDirectSolver); f + M h + D r by
 *    PatternOperators, with the damping split for A = c_M M + c_D D + K;
 *  - the constraints with constant rows (droppers, supports: the *fixed*
 *    ones) by their Schur complement G_F A^-1 G_F^T + C (FixedConstraintSchur:
 *    computed once, sparse, factorised once per selection) and their
 *    truncated columns A^-1 G_F^T;
 *  - the constraints whose rows move (the contacts) by their columns A^-1 G^T
 *    (and A^-1 G_t^T where e != 0) as LocalColumns, solved once per time
 *    point over the rows they reach; they border the fixed block, whose
 *    entries against them are formed only on the fixed rows their reach
 *    meets (solve_bordered()).
 */
class FastConstrainedOperator : public ConstrainedOperator
{
public:
  FastConstrainedOperator(const SemiDiscreteSystem& system, const Definition& definition);

  void set_rows(const std::vector<ConstraintState>& rows, double t) override;
  void apply_inverse(dealii::Vector<double>& x) const override;
  void solve_history(double t, const dealii::Vector<double>& h,
                     const dealii::Vector<double>& r,
                     dealii::Vector<double>& out) override;
  void solve_multipliers(const std::vector<unsigned int>& set, std::vector<double>& y,
                         const char* what) override;
  void add_columns(const std::vector<double>& y, dealii::Vector<double>& x) override;

private:
  /// The fixed and moving constraints, and each one's law.
  void partition();
  /// The Schur complement and the truncated columns of the fixed constraints.
  void initialize_fixed();
  /// A^-1 G^T (column 0) and A^-1 G_t^T (column 1, where e != 0) of the
  /// moving constraints at the rows of set_rows(), once per time point.
  void update_moving_columns();
  /// The border of moving constraint @p i (column c of the bordered system).
  void fill_border(unsigned int c, unsigned int i);
  double compliance(unsigned int i) const
  {
    return definition.compliance.empty() ? 0. : definition.compliance[i];
  }
  double rate_weight(unsigned int i) const
  {
    return definition.rate_weight.empty() ? 0. : definition.rate_weight[i];
  }

  Definition definition;
  MassInverse inverse;                         ///< A^-1
  std::unique_ptr<PatternOperators> operators; ///< made at the first solve_history()
  dealii::Vector<double> shifted;              ///< h + mu r of the damping split

  std::vector<unsigned int> fixed, moving; ///< constraints with constant / moving rows
  std::vector<unsigned int> position;      ///< of constraint i in fixed or moving
  std::vector<char> moves;

  const std::vector<ConstraintState>* rows = nullptr;
  double time = 0.;
  bool columns_current = false;
  std::vector<LocalColumns> columns; ///< per moving constraint

  FixedConstraintSchur schur;
  bool fixed_ready = false;
  /// The fixed constraints on each unknown: those a moving column's reach meets.
  RowsByColumn fixed_at_row;
  std::vector<unsigned int> reached; ///< the fixed constraints a column reaches
  std::vector<char> seen;            ///< RowsByColumn::rows_in()'s workspace
  std::vector<bool> keep;            ///< fixed constraints in the current system
  std::vector<double> factors;       ///< their multipliers (FixedConstraintSchur order)

  /// The bordered system of solve_multipliers(), kept from call to call
  /// (nothing allocated once its sizes are reached).
  std::vector<unsigned int> moving_in; ///< the moving constraints of the set
  dealii::Vector<double> x, z, rhs;
  std::vector<dealii::Vector<double>> Bc, Cr;
  dealii::FullMatrix<double> D;
  std::vector<dealii::Vector<double>*> batch;
};
} // namespace pantocat
