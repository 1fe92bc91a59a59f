#pragma once

#include <pantocat/constrained/half_explicit_step_system.h>
#include <pantocat/constrained_fast/disjoint_fixed_constraints.h>
#include <pantocat/constrained_fast/fixed_constraint_schur.h>
#include <pantocat/constrained_fast/mass_inverse.h>
#include <pantocat/lac/diagonal_force_sweep.h>
#include <pantocat/lac/local_columns.h>

#include <deal.II/lac/full_matrix.h>

#include <initializer_list>

namespace pantocat
{
/**
 * Rows [first, last) of the force sweep of FastHalfExplicitStepSystem that share
 * their coefficients (uniform: f, D/2, the scaling of (M + dt/2 D)^-1, and
 * K(i, i), K(i, i + o), K(i, i - o) for o = 1..3), so that the sweep reads
 * them once instead of once per row; rows with their own stiffness (ends of
 * the bodies) form runs that are not uniform. A row inside a uniform run
 * whose f, D/2 or scaling differ (a dropper's or clamp's point mass, a point
 * load) is an exception of the run: swept with the run, then done again with
 * its own values, so that point masses do not cut a wire into short runs.
 */
/// A row of a uniform run with its own f, D/2 and scaling (see UniformForceRun).
struct ForceException
{
  int row = 0;
  double f = 0., d0 = 0., scale = 0.;
  /// False for a row that is predicted again after the constraints' forces
  /// anyway (DisjointFixedConstraints): the sweep then skips its q*, v*.
  bool predict = true;
};

struct UniformForceRun
{
  int first = 0, last = 0;
  /// The run's exceptions: [first_exception, last_exception) of the integrator's list.
  int first_exception = 0, last_exception = 0;
  bool uniform = false;
  int reach = 1;          ///< the largest o with K(i, i +- o) != 0 in the run
  bool symmetric = false; ///< K(i, i + o) = K(i, i - o) for every o
  double f = 0., d0 = 0., scale = 0., k0 = 0.;
  double upper[3] = {0., 0., 0.}, lower[3] = {0., 0., 0.};
};

/**
 * The fast implementation of HalfExplicitStepSystem: the two levels of
 * (39)-(41) in O(n + m) per step.
 *
 * The forces f - K q_n - D (v_{n-1} + v_n)/2 are swept by diagonals of K and
 * D, with the diagonal scaling of W^-1 = (M + h/2 D)^-1 and the prediction
 * q*, v* of (40) fused into the same pass where W is diagonal (FDM; lumped
 * pantographs add a few coupled rows, whose rows are predicted again from
 * their final a); runs of rows with equal coefficients are swept with their
 * coefficients read once (UniformForceRun). When W is factorised (FEM), the
 * acceleration without the rigid constraints' forces is solved once per
 * step beside the first moving constraint's column.
 *
 * The multiplier systems are split by the rows of the rigid constraints
 * (doc/benchmarks.md, "Constraints"): those with constant rows G_F (droppers,
 * supports) have the constant Schur complements G_F W^-1 G_F^T and
 * G_F M^-1 G_F^T (FixedConstraintSchur: sparse, banded, refactorised only
 * when the active set changes); the few moving ones (the contact) border
 * them, with their columns W^-1 G^T, M^-1 G^T, ... computed each step on the
 * rows they reach. When both complements are diagonal (the FDM's droppers
 * and supports under diagonal M and D: no two share an unknown),
 * DisjointFixedConstraints takes each fixed constraint from its own row in
 * one pass, and the moving ones are bordered only by the fixed ones on their
 * unknowns. In the position level (40), the fixed constraints that held at
 * t_{n-1} and t_n are settled (find_corrected_fixed()): their eta, mu are
 * round-off, and only the others' block is solved and corrected.
 */
class FastHalfExplicitStepSystem : public HalfExplicitStepSystem
{
public:
  FastHalfExplicitStepSystem(const SemiDiscreteSystem& system, double h);

  void set_time_step(double time_step) override;
  void start(const Step& step) override;
  void acceleration_level(const std::vector<unsigned int>& force_set,
                          const std::vector<unsigned int>* next_set) override;
  void position_level(const std::vector<unsigned int>& set) override;
  void finish_step() override;

  /**
   * On (the default), the position level leaves out the corrections of the
   * settled fixed constraints (find_corrected_fixed()); off, every held one
   * is corrected (for the tests that compare the two).
   */
  void settle_fixed_constraints(bool on) { settling = on; }
  /// Number of fixed constraints whose corrections the latest position level left out.
  unsigned int settled_in_latest_step() const { return settled_count; }

private:
  /// The step's vectors (Step).
  const dealii::Vector<double>& q_n() const { return *step.q; }
  const dealii::Vector<double>& v_n() const { return *step.v; }
  dealii::Vector<double>& a_n() const { return *step.a; }
  dealii::Vector<double>& next_q() const { return *step.q_next; }
  dealii::Vector<double>& next_v() const { return *step.v_next; }
  std::vector<double>& multipliers() const { return *step.lambda; }
  std::vector<double>& gaps_next() const { return *step.gaps; }

  /// f += G^T lambda of the compliant constraints, scaled by @p scaling if given.
  void add_compliant_loads(double* f, const double* scaling) const;
  /**
   * The multipliers of the acceleration level g^(II) = 0 of the constraints
   * @p active (step 1): lambda_n, and a += (M + dt/2 D)^-1 G^T lambda_n.
   */
  void add_acceleration_multipliers(const std::vector<unsigned int>& active);
  /// eta, mu of (40) for the constraints split() found, and their corrections of q*, v*.
  void solve_position_and_velocity_level(const std::vector<ConstraintState>& at_n,
                                         const std::vector<ConstraintState>& at_half,
                                         const std::vector<ConstraintState>& at_next);
  /**
   * A fixed constraint (constant row) that held at t_{n-1} and t_n and has a
   * force at t_n is *settled*: G v_{n-1} = G v_n = 0, G q_n = -z and the
   * acceleration level G a_n = 0 give G v* = G v_{n-1} + 2 dt G a_n = 0 and
   * G q* = G q_n + dt G (v_n + v*)/2 = -z, so (40)'s residuals r_g, r_v of its
   * row are round-off, and so are its own eta, mu. Only the other
   * constraints' corrections move its row: those of the moving (contact)
   * constraints whose columns M^-1 G^T reach it (near_M), and through S =
   * G_F M^-1 G_F^T those of the fixed constraints that are not settled. The
   * corrections M^-1 G_k^T (h^2 eta_k + h mu_k) and 2h M^-1 G_k^T eta_k of the
   * settled constraints that S couples to none of those by more than the unit
   * round-off (FixedConstraintSchur::reach_from()) are therefore left out of
   * q_{n+1}, v_{n+1}; the others, corrected_fixed, are found here
   * (correction_kept). A settled constraint is corrected all the same on
   * every settled_refresh_period-th step: the round-off of G a_n = 0 adds to
   * G v of each of the two chains (even and odd steps) of the two-step
   * update, and the drift of g and dg/dt stays bounded (the period is odd, so
   * that the corrections alternate between the chains); it is its own round-off
   * that is corrected then, so S's reach is not followed from it. Returns
   * false (every held constraint corrected) when the step gives no active
   * sets of t_{n-1} and t_n (Step::active_before: the method gives none in
   * the first two steps after a start or a new v_{n-1}, and after an impact,
   * whose jump v_{n-1} then carries).
   */
  bool find_corrected_fixed();
  /**
   * The fixed block [h^2 S, h S; 2h S, 0] of (40) (S = G_F M^-1 G_F^T) applied
   * inversely to each of @p xs (the halves r_g, r_v of each through S side
   * by side): eta = S^-1 r_v / (2h), mu = S^-1 r_g / h - h eta.
   */
  void solve_fixed_position_block(const std::vector<dealii::Vector<double>*>& xs);
  /// x(slot) = -g_k, x(half + slot) = -dg_k/dt of fixed constraint k at q*, v*
  /// (the right-hand sides of (40); its G_t, z_t are 0).
  void set_fixed_residuals(unsigned int k, unsigned int slot, unsigned int half,
                           dealii::Vector<double>& x) const;
  /**
   * (40) with the fixed block restricted to corrected_fixed (S_RR factorised
   * dense, FixedConstraintSchur::factorize_subset()), when they are few: the
   * settled constraints' rows take no part (their eta, mu are round-off).
   */
  void solve_corrected_position_and_velocity_level(
      const std::vector<ConstraintState>& at_n,
      const std::vector<ConstraintState>& at_half,
      const std::vector<ConstraintState>& at_next);
  void compute_moving_columns();
  struct MovingColumns;
  /**
   * The FDM's path (DisjointFixedConstraints): the moving constraints'
   * multipliers bordered by the fixed ones near them (near_fixed), then
   * one pass over the fixed constraints per level.
   */
  void add_disjoint_acceleration_multipliers();
  void
  solve_disjoint_position_and_velocity_level(const std::vector<ConstraintState>& at_n,
                                             const std::vector<ConstraintState>& at_half,
                                             const std::vector<ConstraintState>& at_next);
  /**
   * y, the border B, C = B^T and the moving block D of (39)'s multiplier
   * system from the moving columns Y; @p near_fixed_of(X, visit) calls
   * visit(slot, k) for the fixed constraints k near X (unknown slot).
   */
  template <typename NearFixed>
  void fill_acceleration_border(const NearFixed& near_fixed_of);
  /// lambda and a += (M + dt/2 D)^-1 G^T lambda of the moving constraints
  /// (their multipliers in acceleration_workspace.y).
  void add_moving_acceleration_forces();
  /// near_fixed <- the kept fixed constraints in the moving columns' lists @p near.
  void gather_near_fixed(std::vector<unsigned int> MovingColumns::*near);
  /**
   * y, the border B, C and the moving block D of (40)'s multiplier system
   * from the moving columns; @p near_fixed_of(X, visit) calls visit(slot, k)
   * for the fixed constraints k near X, whose unknowns are slot and
   * @p half + slot.
   */
  template <typename NearFixed>
  void fill_position_border(const std::vector<ConstraintState>& at_next,
                            unsigned int half, const NearFixed& near_fixed_of);
  /// q* += M^-1 (h^2 G^T eta + h G_t^T eta + h G^T mu), v* += 2h M^-1 G^T eta
  /// of the moving constraints (their eta, mu in position_workspace.y).
  void add_moving_position_corrections(const std::vector<ConstraintState>& at_n,
                                       const std::vector<ConstraintState>& at_half);
  /// DisjointFixedConstraints if the fixed constraints qualify, and the rows
  /// refresh_prediction() predicts again.
  void take_disjoint_fixed_constraints();
  /// The columns of one moving constraint when M and M + dt/2 D are factorised.
  /// With @p free_rhs, also free_rhs <- W^-1 free_rhs in W's sweep (beside Y).
  void compute_factorised_columns(const SparseDirectSolver& W,
                                  const SparseDirectSolver& M,
                                  const ConstraintState& at_n,
                                  const ConstraintState& at_half,
                                  const ConstraintState& at_next, MovingColumns& x,
                                  dealii::Vector<double>* free_rhs);
  void reset_moving_columns();
  /// keep[k] for the fixed constraints among @p active, and the moving ones among them.
  void split(const std::vector<unsigned int>& active, std::vector<bool>& keep,
             std::vector<unsigned int>& moving_active);
  /// The same, kept for the last two sets asked for (the force and the active
  /// indices of a step, which seldom change): O(m) only when they do.
  struct ActiveSplit
  {
    bool valid = false;
    unsigned long version = 0; ///< a new number whenever the split is made again
    std::vector<unsigned int> indices, moving;
    std::vector<bool> keep;
  };
  const ActiveSplit& split_of(const std::vector<unsigned int>& active);
  ActiveSplit split_cache[2];
  int next_split_slot = 0;
  unsigned long split_versions = 0;
  unsigned long keep_version = 0; ///< the version of keep
  void factorize();
  /// a <- (M + dt/2 D)^-1 (f - K q - D (v_prev + v)/2 + G_c^T lambda_c), with
  /// the compliant forces lambda_c, in one pass over the
  /// rows where (M + dt/2 D) is diagonal but for a few coupled rows.
  void compute_forces();
  /// out <- f - K q - D (v_prev + v)/2 + G_c^T lambda_c (compute_forces() before its
  /// solve).
  void unscaled_forces(double* out);
  /**
   * When M + dt/2 D is factorised, the acceleration without the rigid
   * constraints' forces, a* = (M + dt/2 D)^-1 (f - K q - D (v_prev + v)/2 +
   * G_c^T lambda_c), does not depend on the active set: start() solves it
   * once per step, with the first moving constraint's columns, and
   * compute_forces() swaps it into a (no copy). A second trial of the step
   * (an active-set iteration) finds it taken and solves it again
   * (solve_free_acceleration(): the same operations, the same bits).
   */
  dealii::Vector<double> free_acceleration;
  bool free_acceleration_ready = false, free_acceleration_taken = false;
  /// free_acceleration = (M + dt/2 D)^-1 (unscaled_forces()), as start()
  /// and compute_moving_columns() make it.
  void solve_free_acceleration();
  /**
   * After compute_forces() predicted q*, v* in its sweep: predicts them again
   * on the rows whose a changed after the sweep (coupled rows, the rows of the
   * constraints' forces), from the final a_n, so that q*, v* are those of
   * the separate pass of acceleration_level() to the bit.
   */
  void refresh_prediction();
  /// q*, v* of (40) on every row from a_n (when compute_forces() did not predict).
  void predict_every_row();
  /// forces: K and D/2 by diagonals, and what the fused sweeps need to know.
  void build_force_diagonals();
  /// f(t_n): the system's constant load, or f(t_n) in load_now if it depends on t.
  const double* load_at_time_n();

  /// K and D/2 stored by diagonals (ForceDiagonals), and what the fused
  /// sweeps need to know about them.
  struct BandedOperator : ForceDiagonals
  {
    struct Entry
    {
      unsigned int row, column;
      double value;
    };
    /// D/2 off the diagonal, and on it too if damped_rows_coupled.
    std::vector<Entry> listed_damping;
    /**
     * True when only the rows of a coupled block (a lumped pantograph's) are
     * damped, e.g. a scene without the wires' damping: the sweep then skips
     * the diagonal of D and its two velocity streams, and the list carries
     * every damper.
     */
    bool damped_rows_coupled = false;
    bool symmetric_stiffness = false; ///< K(i, j) == K(j, i) exactly
  } forces;
  /// f - K q - D (v_prev + v)/2 from the diagonals above, for unscaled_forces()
  /// (whenever compute_forces() does not take its fused, scaled sweep).
  DiagonalForceSweep force_sweep;

  dealii::Vector<double> load_now;      ///< f(t_n), only for a time-dependent load
  MassInverse smoothed_mass_inverse;    ///< (M + dt/2 D)^{-1}
  MassInverse mass_inverse;             ///< M^{-1}
  std::vector<unsigned int> fixed;      ///< rigid constraints with constant rows
  std::vector<unsigned int> moving;     ///< rigid constraints whose rows move
  std::vector<int> position;            ///< of constraint i in fixed or moving
  FixedConstraintSchur fixed_smoothed;  ///< G_F (M + dt/2 D)^-1 G_F^T
  FixedConstraintSchur fixed_mass;      ///< G_F M^-1 G_F^T
  DisjointFixedConstraints disjoint;    ///< the same, one by one, when they qualify
  std::vector<unsigned int> near_fixed; ///< workspace of gather_near_fixed()
  /// The set of the next position_level(), during acceleration_level().
  const std::vector<unsigned int>* update_set = nullptr;
  /// Step 2 of the fixed constraints was done in step 1's pass, but for
  /// deferred_fixed (those near the moving constraints' columns).
  bool projected_early = false;
  std::vector<unsigned int> deferred_fixed;
  std::vector<bool> project_now; ///< true but for deferred_fixed
  /// Columns of a moving constraint, every step: Y = (M+dt/2 D)^-1 G(t_n)^T,
  /// P = M^-1 G(t_n)^T, Q = M^-1 G_t(t_{n+1/2})^T, R = M^-1 G(t_{n+1/2})^T,
  /// and its rows at t_{n+1} against M^-1: U = M^-1 G(t_{n+1})^T, V = M^-1
  /// G_t(t_{n+1})^T.
  struct MovingColumns
  {
    dealii::Vector<double> Y, P, Q, R, U, V;
    /// The fixed constraints whose rows can meet Y, respectively P to V
    /// (all of them when the columns are dense).
    std::vector<unsigned int> near_Y, near_M;
    /// Y (when M + dt/2 D is factorised), P to V (when M is) were solved
    /// locally and are zero off the rows reach_Y, respectively reach_M.
    bool local_Y = false, local_M = false;
    RowRanges reach_Y, reach_M;
  };
  /// x.Y = W^-1 G^T on the rows it reaches (the previous ones reset).
  void compute_local_column(const SparseDirectSolver& W, const SparseRow& G,
                            MovingColumns& x);
  /// y += factor * column, a moving column with the rows @p reach when @p local.
  static void add_moving_column(const MassInverse& A, const SparseRow& row,
                                const dealii::Vector<double>& column, bool local,
                                const RowRanges& reach, double factor,
                                dealii::Vector<double>& y);
  /**
   * @p near <- the fixed constraints (their positions in fixed) whose rows meet
   * a moving column A^-1 rows^T: those on the rows of its reach when it was
   * solved locally (@p local), else those on the rows' unknowns and A's
   * coupled block when A is diagonal, all when A is factorised.
   */
  void find_fixed_near(std::initializer_list<const SparseRow*> rows, const MassInverse& A,
                       bool local, const RowRanges& reach,
                       std::vector<unsigned int>& near);
  /**
   * The rows G_k and offsets z_k of the fixed constraints (constant; G_t,
   * G_tt, z_t, z_tt are 0), stored flat for the per-step loops over them.
   */
  struct FixedRows : CompressedRows
  {
    std::vector<double> offset;
  };
  FixedRows fixed_rows;
  std::vector<SparseRow> fixed_row_list; ///< the same rows, one by one
  std::vector<bool> is_moving;   ///< constraint i is a moving (time-dependent) one
  RowsByColumn fixed_by_unknown; ///< the fixed constraints on each unknown
  std::vector<bool> near_mark;   ///< workspace of find_fixed_near()
  std::vector<MovingColumns> columns;
  /// Workspace of compute_moving_columns().
  LocalColumns local_W, local_M, local_V;
  std::vector<unsigned int> compliant;    ///< indices of the compliant constraints
  std::vector<double> factors, factors_v; ///< workspace
  std::vector<bool> keep;
  std::vector<bool> force_keep; ///< keep of step 1's set (with a force) in the trial
  std::vector<unsigned int> moving_active;
  bool settling = true;           ///< settle_fixed_constraints()
  unsigned int settled_count = 0; ///< settled_in_latest_step()
  /// A settled constraint is corrected all the same every this many steps.
  static constexpr unsigned int settled_refresh_period = 31;
  /// The most corrected constraints solve_corrected_position_and_velocity_level() takes.
  static constexpr unsigned int max_corrected_subset = 32;
  std::vector<unsigned int> corrected_fixed; ///< find_corrected_fixed()
  std::vector<int> corrected_slot;           ///< position in corrected_fixed, or -1
  /// Workspace of find_corrected_fixed(), and its flags (correction_kept[k]).
  std::vector<unsigned int> settle_sources;
  std::vector<bool> correction_kept;
  /**
   * A bordered multiplier system (solve_bordered()): kept from step to step,
   * so that a step allocates nothing.
   */
  struct MultiplierWorkspace
  {
    dealii::Vector<double> x, y, rhs;
    /// The halves (r_g, r_v) of the position level's right-hand sides.
    std::vector<dealii::Vector<double>> halves;
    std::vector<dealii::Vector<double>*> half_pointers;
    std::vector<dealii::Vector<double>> B, C;
    std::vector<dealii::Vector<double>*> batch;
    dealii::FullMatrix<double> D;
    /// x, y, B, C, D zeroed for @p n_fixed fixed and @p n_moving moving unknowns.
    void prepare(unsigned int n_fixed, unsigned int n_moving);
  };
  /// One per level: their sizes differ (m and 2m), so each keeps its vectors.
  MultiplierWorkspace acceleration_workspace, position_workspace;
  /**
   * The runs of rows with equal coefficients for compute_forces(), built at
   * its first call after a change of dt; empty when they would not pay off
   * (many short runs) or the load depends on t.
   */
  void build_uniform_runs(const double* scale);
  /// Each uniform run takes the values most of its rows have (@p own: each
  /// row's f, D/2 and scaling); the others become its exceptions.
  void take_majority_values(const std::vector<ForceException>& own);
  /// Merges the rows outside uniform runs, and keeps the runs if they pay.
  void merge_and_finish_runs();
  std::vector<UniformForceRun> uniform_runs;
  std::vector<ForceException> force_exceptions;
  bool uniform_runs_built = false;
  /// compute_forces() wrote q* and v* into q_new and v_new (the diagonal case).
  bool predicted = false;
  /// Rows refreshed every step by refresh_prediction(): coupled rows, fixed constraints.
  std::vector<unsigned int> constant_refresh_rows;
};
} // namespace pantocat
