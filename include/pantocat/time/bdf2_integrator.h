#pragma once

#include <pantocat/lac/sparse_direct_solver.h>
#include <pantocat/time/active_set.h>
#include <pantocat/time/constraint_evaluator.h>
#include <pantocat/time/constraint_response_cache.h>
#include <pantocat/time/mass_inverse.h>
#include <pantocat/time/time_integrator.h>

#include <deal.II/lac/full_matrix.h>

#include <memory>

namespace pantocat
{
/**
 * Two-step BDF on the GGL-stabilised index-2 formulation (38) (Sec. 5.2),
 * with the Richardson start of Sec. 5.2 (backward Euler with dt and twice
 * dt/2, extrapolated) and the active-set strategy of Sec. 5.3.
 *
 * With the BDF derivative D_h x = c x_{n+1} - rho_x (BDF2: c = 3/(2 dt),
 * rho = (4 x_n - x_{n-1})/(2 dt); Euler: c = 1/dt, rho = x_n/dt), every step
 * solves the linear system
 *
 *   M (D_h q - v) = G_t^T eta + G^T mu,   M (D_h v - a) = G^T eta,
 *   M a + D v + K q = f + G^T lambda,
 *   g = 0, dg/dt = 0, d2g/dt2 = 0 (active constraints, rows at t_{n+1}).
 *
 * Block elimination reduces the (q, v, a) part to the constant matrix
 * S = K + c D + c^2 M, factorised once per c with a sparse direct solver; the
 * multipliers come from a 3m x 3m dense system (m active constraints).
 */
class Bdf2Integrator : public TimeIntegrator
{
public:
  /**
   * With @p cache_responses (the default) the BDF-2 steps use a
   * ConstraintResponseCache while the constraint rows touch at most
   * max_cached_unknowns unknowns (coarse grids, where the contact load covers
   * few cells): one solve with S per step instead of a solve per constraint
   * column. Otherwise every step solves for all columns (also the reference
   * the tests compare with).
   */
  Bdf2Integrator(const SemiDiscreteSystem& system, double time_step,
                 unsigned int max_active_set_iterations, bool cache_responses = true);
  ~Bdf2Integrator() override;

  std::string name() const override { return "bdf2"; }
  void initialize(const DynamicState& initial) override;
  void advance() override;
  const DynamicState& latest() const override { return current; }
  double time() const override { return current.t; }

  /// (q, v, a) of the block system.
  struct Triple
  {
    dealii::Vector<double> q, v, a;
    void reinit(unsigned int n);
    void add(double factor, const Triple& other);
  };

private:
  struct Stage; ///< factorisation and constant columns for one value of c

  /// One implicit step from history (rho_q, rho_v) to time t1 with stage @p s.
  DynamicState implicit_step(Stage& s, const dealii::Vector<double>& rho_q,
                             const dealii::Vector<double>& rho_v, double t1,
                             const std::vector<bool>& active_at_start);
  void richardson_start();
  /// Number of distinct unknowns in the constraint rows at @p t1.
  unsigned int unknowns_touched(double t1);
  /// Above this many touched unknowns the column solves are cheaper than the cache.
  static constexpr unsigned int max_cached_unknowns = 40;
  /// One BDF-2 step with the response cache (same equations as implicit_step).
  DynamicState cached_step(const dealii::Vector<double>& rho_q,
                           const dealii::Vector<double>& rho_v, double t1,
                           const std::vector<bool>& active_at_start);

  double dt;
  MassInverse mass_inverse;
  ConstraintEvaluator at_next;
  ActiveSetIteration active_set;
  std::unique_ptr<Stage> bdf2;
  bool use_cache;
  std::unique_ptr<ConstraintResponseCache> responses;
  std::vector<int> position_in_U; ///< unknown -> position in the rows' index set, or -1
  DynamicState previous, current;
  unsigned long step_number = 0;
  dealii::FullMatrix<double> small;
  dealii::Vector<double> small_rhs, small_solution;
};
} // namespace pantocat
