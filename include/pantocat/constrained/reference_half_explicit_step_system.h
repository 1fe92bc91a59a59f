#pragma once

#include <pantocat/constrained/half_explicit_step_system.h>
#include <pantocat/constrained/reference_constrained_operator.h>

#include <map>
#include <memory>

namespace pantocat
{
/**
 * The plain HalfExplicitStepSystem, the oracle of the fast one: the forces
 * of (39) by sparse matrix-vector products, W^-1 = (M + h/2 D)^-1 and the
 * acceleration level's multipliers by a ReferenceConstrainedOperator (full
 * UMFPACK solves, a dense multiplier system); the position level (40) with
 * one full solve with M per column and its 2p x 2p multiplier system
 * assembled dense, as (40) reads, and solved by LAPACK's LU factorisation.
 */
class ReferenceHalfExplicitStepSystem : public HalfExplicitStepSystem
{
public:
  ReferenceHalfExplicitStepSystem(const SemiDiscreteSystem& system, double h);

  void set_time_step(double time_step) override;
  void start(const Step& step) override;
  void acceleration_level(const std::vector<unsigned int>& force_set,
                          const std::vector<unsigned int>* next_set) override;
  void position_level(const std::vector<unsigned int>& set) override;

private:
  /// The columns of constraint j's eta and mu in q and v of (40).
  struct Corrections
  {
    dealii::Vector<double> q_eta, q_mu, v_eta;
  };
  Corrections corrections_of(unsigned int j);
  /**
   * M^-1 @p row^T of constraint @p j; kept for a @p constant row (the
   * constraint's rows do not depend on t), else valid until the next call.
   */
  const dealii::Vector<double>& mass_column(const SparseRow& row, unsigned int j,
                                            bool constant);

  std::unique_ptr<ReferenceConstrainedOperator> W; ///< M + h/2 D
  ReferenceConstrainedOperator M;
  std::map<unsigned int, dealii::Vector<double>> constant_columns;
  dealii::Vector<double> moving_column;
};
} // namespace pantocat
