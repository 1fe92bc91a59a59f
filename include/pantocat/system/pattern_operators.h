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
  /// Rows that history() sums from a stretch's coefficients (exceptions not counted).
  unsigned int rows_in_stretches() const;

  /// Stretches shorter than this are left to the runs.
  static constexpr unsigned int minimum_stretch = 32;

private:
  /// Rows first + r stride (r < rows) with entries at first_offset .. +
  /// n_offsets of `offsets`; the value of entry e of row r at values + e rows + r.
  struct Run
  {
    unsigned int first, stride, rows, first_offset, n_offsets;
    std::size_t values;
    /// Distance between the values of two offsets (the rows of the whole run;
    /// more for the pieces of a run that history() takes).
    unsigned int leading = rows;
  };

  /// The entries of row @p i: offsets and M, D values in the pattern's order.
  struct RowEntries
  {
    std::vector<int> offsets;
    std::vector<double> mass, damping;
    bool operator==(const RowEntries& o) const
    {
      return offsets == o.offsets && mass == o.mass && damping == o.damping;
    }
  };
  /// Rows [first, last) whose entries are those of row first (even distance)
  /// or first + 1 (odd distance) but for n_exceptions rows; the rows'
  /// offsets merged in the pattern's order.
  struct Stretch
  {
    unsigned int first, last, n_exceptions;
    std::vector<int> offsets;
    std::vector<double> mass, damping; ///< [offset index * 2 + parity], 0 where absent
    /// The exceptions whose offsets are among the stretch's, four per group
    /// (the last group repeats its last row): rows [group][lane], their M and
    /// D values [group][offset index][lane] (0 where absent).
    std::vector<unsigned int> grouped_rows;
    std::vector<double> grouped_mass, grouped_damping;
    /// Groups the exceptions @p rows with entries @p entries.
    void group(const std::vector<unsigned int>& rows,
               const std::vector<const RowEntries*>& entries);
  };
  RowEntries row_entries(unsigned int i) const;
  void find_stretches();
  /// The runs without the stretches' rows: history()'s pieces of runs.
  void cut_runs_at_stretches();
  template <typename Pass>
  void for_each_block(const std::vector<Run>& pieces, const Pass& pass) const;

  const SemiDiscreteSystem& system;
  mutable dealii::Vector<double> load; ///< f(t) of the latest set_time()
  std::vector<Run> runs;
  std::vector<int> offsets;
  std::vector<double> mass, damping, stiffness;
  std::vector<Stretch> stretches;
  std::vector<Run> history_runs; ///< the runs' rows outside the stretches
  /// Exceptions with offsets outside their stretch's, summed alone, and their entries.
  std::vector<unsigned int> exceptions;
  std::vector<RowEntries> exception_entries;
};
} // namespace pantocat
