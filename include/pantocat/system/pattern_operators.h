#pragma once

#include <pantocat/lac/interleaved_columns.h>
#include <pantocat/lac/sparse_direct_solver.h>
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
 *
 * **The damping split** (fewer terms per row). Given the factors
 * of an integrator's iteration matrix S = s_M M + s_D D + s_K K (BDF-2 of
 * (38): c^2, c, 1), the operators split D on each block where the damping
 * is proportional, D = alpha M + beta K (the viscous beta w_t of Eq. (2):
 * D = beta M of the wire; Rayleigh damping), but for the rows E that break
 * the law (point masses outside it, springs):
 *
 *     D r = mu M r + gamma S r + E r,   gamma = beta / (s_K + s_D beta),
 *     mu = alpha - gamma (s_M + s_D alpha),   E = D - mu M - gamma S,
 *
 * so that S^-1 (f + M h + D r) = gamma r + S^-1 (f + M (h + mu r) + E r).
 * history() then sums f + M h' + E r, where the caller passes h' = h + mu r
 * (shifts() gives mu and gamma of each block's rows) and adds gamma r to the
 * solution (add_shift()). On the rows where E is zero, the stretches' passes
 * sum the mass's entries alone: half the terms of f + M h + D r. Entries of
 * E below 1e-12 of the largest terms of their row are round-off and taken as
 * zero. Blocks where half the rows or more break every law tried, or of
 * fewer than 32 rows, keep D (mu = gamma = 0), and so does a system whose
 * blocks do not tile its rows.
 */
class PatternOperators
{
public:
  /// The factors of S = mass M + damping D + stiffness K.
  struct IterationFactors
  {
    double mass, damping, stiffness;
  };
  /// Rows [first, last) of one block and its split of the damping.
  struct Shift
  {
    unsigned int first, last;
    double mu, gamma;
  };

  /// history() with D (no split).
  explicit PatternOperators(const SemiDiscreteSystem& system);
  /// history() with the damping split for the iteration matrix @p split
  /// (see the class comment); motion() is not available.
  PatternOperators(const SemiDiscreteSystem& system, const IterationFactors& split);

  /// Uses f(@p t) from now on; nothing to do if the system's load is constant.
  void set_time(double t) const;

  /// @p out = f + M h + D r; with the damping split, f + M h + E r (h = h' of
  /// the class comment).
  void history(const dealii::Vector<double>& h, const dealii::Vector<double>& r,
               dealii::Vector<double>& out) const;

  /// The blocks' rows with their mu and gamma, in order, covering all rows
  /// (mu = gamma = 0 without the split and on the blocks that keep D).
  const std::vector<Shift>& shifts() const { return block_shifts; }
  /// x += gamma r on the rows of each block with gamma != 0.
  void add_shift(const dealii::Vector<double>& r, dealii::Vector<double>& x) const;
  /// @p out = S^-1 (f + M h + D r): history(), the solve with @p inverse (the
  /// factorisation of S; of the S the split was made for, with the split) and
  /// add_shift() in turn; @p h is h' with the split.
  void solve_history(const dealii::Vector<double>& h, const dealii::Vector<double>& r,
                     const SparseDirectSolver& inverse,
                     dealii::Vector<double>& out) const;
  /// Rows whose E (or D without the split) has an entry that is not zero.
  unsigned int rows_with_damping_entries() const;

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
    /// All damping coefficients zero: history() sums the mass's terms alone.
    bool undamped = false;
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
  void build();
  /// mu and gamma of each block for the iteration matrix @p s (see the class comment).
  void split_damping(const IterationFactors& s);
  /// The damping entries stored for row @p i in the pattern's order: D's, or
  /// E's with the split.
  std::vector<double> damping_row(unsigned int i) const;
  /// The shift of the block that holds row @p i.
  const Shift& shift_of(unsigned int i) const;
  void find_stretches();
  /// The runs without the stretches' rows: history()'s pieces of runs.
  void cut_runs_at_stretches();
  template <typename Pass>
  void for_each_block(const std::vector<Run>& pieces, const Pass& pass) const;

  const SemiDiscreteSystem& system;
  std::vector<Shift> block_shifts;
  /// With the split: S's factors.
  bool split = false;
  IterationFactors factors{0., 0., 0.};
  /// rows_with_damping_entries(), counted by find_stretches().
  unsigned int damped_rows = 0;
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
