#pragma once

#include <pantocat/lac/sparse_direct_solver.h>
#include <pantocat/system/semi_discrete_system.h>

#include <deal.II/lac/vector.h>

#include <memory>
#include <string>
#include <vector>

namespace pantocat
{
/**
 * The implementation behind a ConstrainedOperator: `fast` (the structured
 * solves of the constrained_fast folder: Schur complements of the fixed rows,
 * truncated and local columns, bordered moving rows) or `reference` (plain
 * full solves and dense multiplier systems: the oracle of the tests).
 */
enum class LinearAlgebra
{
  fast,
  reference
};

const char* to_string(LinearAlgebra algebra);

/**
 * A constant symmetric positive definite operator A of a time-integration
 * method on the semi-discrete system (35), A = c_M M + c_D D + c_K K (the mass
 * matrix M, M + dt/2 D of the half-explicit method (39)-(41), the iteration
 * matrix S = K + c_v D + c_q M of an implicit step), factorised once, with the
 * multiplier systems of one level of the constraints on it. This is all the
 * linear algebra a method writes:
 *
 *  - apply A^-1, and solve A x = f(t) + M h + D r (the known part of an
 *    implicit step);
 *  - add A^-1 G^T y to a vector (the constraint forces or corrections G^T y);
 *  - solve the multiplier system of one level on a set J of constraints,
 *
 *        sum_{j in J} (G_i + e_i G_t,i) A^-1 G_j^T y_j + C_i y_i = r_i,  i in J,
 *
 *    i.e. ((G + E G_t) A^-1 G^T + C) y = r restricted to J: the rigid
 *    constraints of J with C_i = e_i = 0 (g = 0 or dg/dt = 0 of a level),
 *    the compliant ones with their compliance C_i on the diagonal and the
 *    weight e_i of their rate (a law lambda/k + g + d dg/dt = 0 taken at the
 *    end of the step, Constraint::is_compliant).
 *
 * The constraints are those of the system, by index; their rows G_i, G_t,i
 * at a time point come from set_rows(). C and e are constant per operator
 * (Definition). How the solves are done is the implementation's business:
 * make_constrained_operator() selects it.
 */
class ConstrainedOperator
{
public:
  /// What A is and how the constraints' rows enter its multiplier systems.
  struct Definition
  {
    /// A = mass M + damping D + stiffness K.
    double mass = 1., damping = 0., stiffness = 0.;
    /// C_i per constraint (empty: all 0).
    std::vector<double> compliance;
    /// e_i per constraint (empty: all 0).
    std::vector<double> rate_weight;
    /// Names A in errors (a singular matrix).
    std::string what = "matrix";
    /// The sparse direct solver of A (the fast implementation).
    LinearSolverType solver = LinearSolverType::banded;
  };

  explicit ConstrainedOperator(const SemiDiscreteSystem& system) : system(system) {}
  virtual ~ConstrainedOperator() = default;

  /**
   * The rows (G, G_t, z, ...) of every constraint at time @p t, kept by
   * reference until the next call: the solves that follow use them. Cheap
   * when called again for the same @p t.
   */
  virtual void set_rows(const std::vector<ConstraintState>& rows, double t) = 0;

  /// x <- A^-1 x.
  virtual void apply_inverse(dealii::Vector<double>& x) const = 0;

  /// @p out = A^-1 (f(@p t) + M @p h + D @p r).
  virtual void solve_history(double t, const dealii::Vector<double>& h,
                             const dealii::Vector<double>& r,
                             dealii::Vector<double>& out) = 0;

  /**
   * Solves ((G + E G_t) A^-1 G^T + C) y = r on the constraints @p set (rows
   * of set_rows()): @p y holds r_i for i in @p set on entry (one entry per
   * constraint; the others are not read) and y on return (0 outside
   * @p set). Throws SimulationError naming the time and @p what if the
   * system is singular (linearly dependent constraints).
   */
  virtual void solve_multipliers(const std::vector<unsigned int>& set,
                                 std::vector<double>& y, const char* what) = 0;

  /// x += A^-1 G^T y (one entry of @p y per constraint; zeros add nothing).
  virtual void add_columns(const std::vector<double>& y, dealii::Vector<double>& x) = 0;

  /**
   * The projection of one level: y on @p set with
   * residual(i) + (G_i + e_i G_t,i) A^-1 G^T y + C_i y_i = 0, then
   * x += A^-1 G^T y (with A = M and the gaps g or their rates dg/dt as
   * residuals: x onto g = 0 or dg/dt = 0). y in @p multipliers, 0 outside
   * @p set.
   */
  template <typename Residual>
  void project(const std::vector<unsigned int>& set, const Residual& residual,
               dealii::Vector<double>& x, std::vector<double>& multipliers,
               const char* what)
  {
    multipliers.assign(system.n_constraints(), 0.);
    if (set.empty())
      return;
    for (const unsigned int i : set)
      multipliers[i] = -residual(i);
    solve_multipliers(set, multipliers, what);
    add_columns(multipliers, x);
  }

protected:
  const SemiDiscreteSystem& system;
};

/// A of @p definition on @p system, done by @p algebra.
std::unique_ptr<ConstrainedOperator>
make_constrained_operator(const SemiDiscreteSystem& system,
                          const ConstrainedOperator::Definition& definition,
                          LinearAlgebra algebra);

/**
 * The mass matrix M (the projections of impacts and consistent starts in
 * every method), done by @p algebra, with @p solver for a non-diagonal M.
 */
std::unique_ptr<ConstrainedOperator>
make_mass_operator(const SemiDiscreteSystem& system, LinearAlgebra algebra,
                   LinearSolverType solver = LinearSolverType::banded);
} // namespace pantocat
