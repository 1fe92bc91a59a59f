#pragma once

#include <pantocat/lac/interleaved_columns.h>
#include <pantocat/system/semi_discrete_system.h>

#include <deal.II/lac/vector.h>

#include <cstddef>
#include <vector>

namespace pantocat
{
/**
 * M, D, K and f of the semi-discrete system (35) as plain arrays on the
 * sparsity pattern they share, for the passes of the implicit integrators
 * that need two or three of them at once, in one sweep over the rows:
 *  - history(): f + M h + D r, the known part of the right-hand side of a
 *    BDF-2 or generalized-alpha step;
 *  - motion(): M (q' - v) and M v' + D v + K q - f, the equations of motion
 *    in IDA's residual.
 *
 * The rows are kept in runs of rows i, i + s, i + 2 s, ... (stride s = 1 for
 * a string's nodes, 2 for a Hermite beam's values and slopes) whose entries
 * lie at the same offsets j - i in the same order, the values of each offset
 * contiguous over the run: a pass runs down the rows of a run for one offset
 * after the other, several rows at once, and each row's sum still takes its
 * entries in the pattern's order (the same value, to the bit, as a loop over
 * the row's entries).
 */
class PatternOperators
{
public:
  explicit PatternOperators(const SemiDiscreteSystem& system);

  /// Uses f(@p t) from now on; nothing to do if the system's load is constant.
  void set_time(double t) const;

  /// @p out = f + M h + D r.
  void history(const dealii::Vector<double>& h, const dealii::Vector<double>& r,
               dealii::Vector<double>& out) const;

  /// r_q = M (qp - v), r_v = M vp + D v + K q - f (arrays of length n).
  void motion(const double* q, const double* v, const double* qp, const double* vp,
              double* r_q, double* r_v) const;

  /// Number of runs of rows with the same offsets (see the class comment).
  std::size_t n_runs() const { return runs.size(); }

private:
  /// Rows first + r stride (r < rows) with entries at first_offset .. +
  /// n_offsets of `offsets`; the value of entry e of row r at values + e rows + r.
  struct Run
  {
    unsigned int first, stride, rows, first_offset, n_offsets;
    std::size_t values;
  };

  const SemiDiscreteSystem& system;
  mutable dealii::Vector<double> load; ///< f(t) of the latest set_time()
  std::vector<Run> runs;
  std::vector<int> offsets;
  std::vector<double> mass, damping, stiffness;
};
} // namespace pantocat
