#pragma once

#include <pantocat/lac/interleaved_columns.h>
#include <pantocat/system/semi_discrete_system.h>

#include <deal.II/lac/vector.h>

#include <vector>

namespace pantocat
{
/**
 * M, D, K and f of the semi-discrete system (35) as plain arrays on the
 * sparsity pattern they share, for the passes of the implicit integrators
 * that need two or three of them at once, in one sweep over the rows:
 *  - history(): f + M h + D r, the known part of the right-hand side of a
 *    BDF-2 or generalized-alpha step, written into one column of a batch;
 *  - motion(): M (q' - v) and M v' + D v + K q - f, the equations of motion
 *    in IDA's residual.
 */
class PatternOperators
{
public:
  explicit PatternOperators(const SemiDiscreteSystem& system);

  /// Uses f(@p t) from now on; nothing to do if the system's load is constant.
  void set_time(double t) const;

  /// Column k of @p out = f + M h + D r.
  void history(const dealii::Vector<double>& h, const dealii::Vector<double>& r,
               InterleavedColumns& out, unsigned int k) const;

  /// r_q = M (qp - v), r_v = M vp + D v + K q - f (arrays of length n).
  void motion(const double* q, const double* v, const double* qp, const double* vp,
              double* r_q, double* r_v) const;

private:
  const SemiDiscreteSystem& system;
  mutable dealii::Vector<double> load; ///< f(t) of the latest set_time()
  std::vector<unsigned int> row_start, column;
  std::vector<double> mass, damping, stiffness;
};
} // namespace pantocat
