#pragma once

#include <pantocat/lac/sparse_direct_solver.h>
#include <pantocat/system/sparse_row.h>
#include <pantocat/time/mass_inverse.h>

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <vector>

namespace pantocat
{
/**
 * Responses of the constant BDF matrices to unit loads on the few unknowns
 * that constraint rows touch: for each such unknown i,
 *
 *   s_i = S^-1 e_i,   m_i = M^-1 e_i,   t_i = S^-1 D M^-1 e_i,
 *
 * with S = K + c D + c^2 M. The contact row moves along the wire, but only by
 * a cell every few dozen steps, so a step needs new responses rarely, and the
 * multipliers' system and the constraint corrections become small dense
 * products and a few vector updates instead of solves (doc/dynamics.md).
 */
class ConstraintResponseCache
{
public:
  ConstraintResponseCache(const SparseDirectSolver& S, const MassInverse& M,
                          const dealii::SparseMatrix<double>& D);

  /// Makes the responses of every index of @p rows available; drops the others.
  void update(const std::vector<const SparseRow*>& rows);

  enum class Operator
  {
    S,  ///< S^-1
    M,  ///< M^-1
    SDM ///< S^-1 D M^-1
  };

  /// l . A r^T for the sparse rows l, r and A one of the three operators.
  double form(const SparseRow& l, Operator A, const SparseRow& r) const;

  /// y += factor * A r^T.
  void add(Operator A, const SparseRow& r, double factor,
           dealii::Vector<double>& y) const;

  /// Responses computed so far (each costs two S solves and one M solve).
  unsigned long n_computed() const { return computed; }

  /// The response of @p A to a unit load on unknown @p dof (which update() must have
  /// seen).
  const dealii::Vector<double>& response(unsigned int dof, Operator A) const;

private:
  struct Response
  {
    dealii::Vector<double> s, m, t;
  };

  const SparseDirectSolver& S;
  const MassInverse& M;
  const dealii::SparseMatrix<double>& D;
  std::vector<int> slot_of; ///< unknown -> slot in pool, or -1
  std::vector<Response> pool;
  std::vector<int> free_slots;
  std::vector<char> wanted;
  std::vector<unsigned int> cached; ///< unknowns with a slot
  unsigned long computed = 0;
};
} // namespace pantocat
