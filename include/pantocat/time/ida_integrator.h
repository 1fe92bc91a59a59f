#pragma once

#include <pantocat/constrained/constrained_operator.h>
#include <pantocat/time/constraint_evaluator.h>
#include <pantocat/time/integrator_registry.h>
#include <pantocat/time/time_integrator.h>

#include <memory>
#include <vector>

namespace pantocat
{
/// The sparse direct solver of IDA's Newton iterations.
enum class IdaLinearSolver
{
  sundials_klu, ///< SUNDIALS' SUNLinSol_KLU (SuiteSparse KLU)
  trilinos_klu, ///< Trilinos Amesos KLU through SparseDirectSolver
  umfpack       ///< deal.II's UMFPACK through SparseDirectSolver
};

/**
 * SUNDIALS IDA (the IDAS library that deal.II links, through its C API:
 * deal.II 9.4's wrapper has no root finding) on the GGL-stabilised index-2
 * system of (38) without the acceleration-level multiplier:
 *
 *   M (q' - v) = G^T mu,   M v' + D v + K q = f + G^T lambda,
 *   G q + z = 0,   G_t q + G v + z_t = 0     (active constraints),
 *   lambda_i = mu_i = 0                      (inactive ones),
 *
 * with y = (q, v, lambda, mu); lambda and mu are algebraic and excluded from
 * the error test. Variable order and step, tolerances from the prm; the
 * sparse Jacobian dF/dy + cj dF/dy' is assembled from M, D, K and the
 * constraint rows and factorised by KLU (SUNDIALS' SUNLinSol_KLU, the
 * default), by Trilinos Amesos KLU or by UMFPACK (through SparseDirectSolver).
 *
 * Events are located by IDA's root finding: the gap of each inactive
 * unilateral constraint (closing) and the multiplier of each active one
 * (release), decreasing through zero. At a root the integration stops; a
 * closing constraint closes with an inelastic impact (positions and
 * velocities projected onto g = dg/dt = 0 with M^-1 G^T), the multipliers
 * are recomputed on acceleration level, constraints with a negative force are
 * released (they separate), and IDA restarts from this consistent state.
 * The multipliers of the velocity projection at a closing event are the
 * impulses [N s] of the impact, reported with the next output point
 * (DynamicState::impulse).
 * advance() integrates to the next output time t + dt.
 *
 * Compliant constraints (Constraint::is_compliant) are forces: F_v -= G^T
 * lambda with the algebraic row lambda = -k g - c dg/dt while engaged and
 * lambda = 0 while not (mu = 0 always): the max() of the force law, whose
 * branch switches at roots of h = max(g, g + (c/k) dg/dt) (engaged iff
 * h < 0), located by the same root finding and restart as the rigid events;
 * they never enter the projections of an event.
 */
class IdaIntegrator : public TimeIntegrator
{
public:
  /// Its entry in registered_integrators().
  static IntegratorEntry registry_entry();

  /**
   * @p maximum_order bounds IDA's BDF order (1-5): orders above 2 are not
   * A-stable, and on an undamped wire with the high frequencies of the C1
   * Hermite elements they cost steps far below those frequencies' periods
   * (doc/dynamics.md, "IDA").
   */
  IdaIntegrator(const SemiDiscreteSystem& system, double output_step,
                double relative_tolerance, double absolute_tolerance,
                IdaLinearSolver solver = IdaLinearSolver::sundials_klu,
                LinearAlgebra algebra = LinearAlgebra::fast,
                unsigned int maximum_order = 2);
  ~IdaIntegrator() override;

  std::string name() const override { return "ida"; }
  void initialize(const DynamicState& initial) override;
  void advance() override;
  const DynamicState& latest() const override { return current; }
  double time() const override { return current.t; }

private:
  struct Sundials; ///< IDA memory, vectors, matrix, linear solver, callbacks (C API)

  /// Impact projection, multipliers on acceleration level, releases: a
  /// consistent state for the set @p active at time t, written into y, y'.
  void make_consistent(double t, std::vector<bool> active);
  /// The rigid constraints of @p set (those the projections hold).
  std::vector<unsigned int> held_rigid(const std::vector<bool>& set) const;
  /**
   * @p a from M a = f - K q - D v + G^T lambda with the compliant forces of
   * @p set and the rigid ones' lambda on acceleration level (G a + 2 G_t v +
   * G_tt q + z_tt = 0), all into @p lambda.
   */
  void accelerations(double t, const std::vector<ConstraintState>& rows,
                     const std::vector<bool>& set, const dealii::Vector<double>& q,
                     const dealii::Vector<double>& v, dealii::Vector<double>& a,
                     std::vector<double>& lambda);
  /// The switches from the active set to @p set, in the statistics; @p set active.
  void record_events(double t, const std::vector<bool>& set, bool closes,
                     const std::vector<double>& event_impulse);
  void read_state(double t);
  /**
   * The sign test of Sec. 5.3 at the output point @p t: the root finding
   * sees lambda_i at the ends of IDA's own steps, so a force that falls
   * through zero and rises again inside one step escapes it. A negative
   * force of an active rigid unilateral constraint at @p t is that release,
   * located at @p t: make_consistent() without it, and IDA restarts there.
   */
  void release_pulling_constraints(double t);
  /// IDA from the state in y, y' at @p t (after make_consistent()).
  void restart(double t);
  /// The root function of compliant unilateral constraint @p k at (q, v).
  double compliant_root(unsigned int k, const ConstraintState& c, const double* q,
                        const double* v) const;
  void collect_counters();

  double dt;
  double rtol, atol;
  unsigned int max_order;
  IdaLinearSolver linear_solver;
  unsigned int n, m;
  std::unique_ptr<ConstrainedOperator> M; ///< of the projections
  ConstraintEvaluator rows;
  dealii::Vector<double> load_scratch;
  std::unique_ptr<Sundials> sun;
  std::vector<bool> active;
  /// Impulses [N s] of the impacts since the last output point (empty: none).
  std::vector<double> pending_impulse;
  DynamicState current;
  std::vector<std::pair<std::string, long>> counted; ///< IDA's counters before restarts
};
} // namespace pantocat
