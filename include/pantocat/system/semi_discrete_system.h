#pragma once

#include <pantocat/system/block_operator.h>
#include <pantocat/system/constraint.h>

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <memory>
#include <string>
#include <vector>

namespace pantocat
{
/// A contiguous range of unknowns that belongs to one body.
struct DofBlock
{
  std::string name;
  unsigned int first = 0;
  unsigned int size = 0;
};

/**
 * A load that changes with time, added to the constant load f of the system:
 * e.g. a prescribed force moving along the contact wire.
 */
class TimeDependentLoad
{
public:
  virtual ~TimeDependentLoad() = default;
  /// f += (this load at time @p t).
  virtual void add_to(double t, dealii::Vector<double>& f) const = 0;
};

/**
 * The semi-discrete constrained system (35) that every integrator consumes:
 *
 *   M a + D v + K q = f + G(t)^T lambda,   g(t, q) = G(t) q + z(t) >= 0 (or = 0),
 *
 * with constant sparse M, D, K (A_Delta = -K), a load f(t) (a constant part
 * plus, only if a scene has them, time-dependent loads), and a list of scalar
 * constraints. Integrators see only this: no wires, no elements.
 * The unknowns are ordered by blocks (carrier, contact wire, pantograph, ...).
 */
class SemiDiscreteSystem
{
public:
  /// Builds the block-diagonal M, D, K and f from the bodies' operators.
  void set_blocks(const std::vector<const BlockOperator*>& bodies);

  void add_constraint(std::unique_ptr<Constraint> constraint);
  void add_time_dependent_load(std::unique_ptr<TimeDependentLoad> load);

  /// True if f depends on t: integrators then evaluate load_at() once per step.
  bool has_time_dependent_load() const { return !time_dependent_loads.empty(); }
  /// f(t) = load + the time-dependent loads at @p t.
  void load_at(double t, dealii::Vector<double>& f) const;

  unsigned int n_dofs() const { return load.size(); }
  unsigned int n_constraints() const { return constraints.size(); }
  /// True if any constraint is compliant (a force law, Constraint::is_compliant).
  bool has_compliant_constraints() const;
  const DofBlock& block(const std::string& name) const;
  bool has_block(const std::string& name) const;

  /**
   * Kinetic energy v^T M v / 2 plus strain energy q^T K q / 2 minus f(t)^T q,
   * plus the strain energy of the compliant constraints at @p t:
   * k/2 min(g, 0)^2 (unilateral) or k/2 g^2 (bilateral), Constraint::strain_energy.
   */
  double energy(const dealii::Vector<double>& q, const dealii::Vector<double>& v,
                double t = 0.) const;
  /// The part of energy() that is not a quadratic form of M or K:
  /// -f(t)^T q plus the compliant constraints' strain energy.
  double potential_of_loads_and_springs(const dealii::Vector<double>& q, double t) const;

  std::vector<DofBlock> blocks;
  /// On the heap, so that the matrices that point to it survive moves of the system.
  std::unique_ptr<dealii::SparsityPattern> sparsity;
  dealii::SparseMatrix<double> mass, damping, stiffness;
  dealii::Vector<double> load;
  bool mass_is_diagonal = true;
  /**
   * False if K is singular without the constraints (a body that only its
   * bilateral constraints hold, BlockOperator::stiffness_is_definite): the
   * static problem is then solved as the saddle-point system
   * (StaticEquilibriumSolver), never by K^-1.
   */
  bool stiffness_is_definite = true;
  std::vector<std::unique_ptr<Constraint>> constraints;
  std::vector<std::unique_ptr<TimeDependentLoad>> time_dependent_loads;
};
} // namespace pantocat
