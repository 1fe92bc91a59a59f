#pragma once

#include <pantocat/constrained/constrained_operator.h>
#include <pantocat/lac/sparse_direct_solver.h>
#include <pantocat/system/semi_discrete_system.h>

#include <deal.II/lac/vector.h>

#include <memory>
#include <vector>

namespace pantocat
{
/**
 * The linear system of one implicit step of the stabilised index-2
 * formulation (38) (Sec. 5.2) with a BDF derivative D_h x = c x - rho_x
 * (BDF-2: c = 3/(2 dt), rho_x = (4 x_n - x_{n-1})/(2 dt); backward Euler:
 * c = 1/dt, rho_x = x_n/dt):
 *
 *   M (D_h q - v) = G_t^T eta + G^T mu,   M (D_h v - a) = G^T eta,
 *   M a + D v + K q = f(t) + G^T lambda,
 *
 * with, per constraint i by its Role in the step (rows at t):
 *
 *  - force (active, carrying a force): g = 0, dg/dt = 0, d2g/dt2 = 0 with
 *    lambda_i, eta_i, mu_i;
 *  - touching (holds without force: an impact's closing constraint):
 *    g = 0, dg/dt = 0 with eta_i, mu_i (lambda_i = 0);
 *  - engaged (an engaged compliant constraint, Constraint::is_compliant):
 *    lambda_i / k + g + (d/k) dg/dt = 0 with lambda_i;
 *  - none: no equation, no multiplier.
 *
 * Eliminating v and a gives q = S^-1 (f + M (rho_v + c rho_q) + D rho_q +
 * G^T (lambda + eta) + c G_t^T eta + c G^T mu + D M^-1 (G_t^T eta +
 * G^T mu)), S = K + c D + c^2 M, and a multiplier system of the three levels
 * (doc/dynamics.md). How it is solved is the implementation's business
 * (make_implicit_step_system()): the reference forms the multiplier system
 * densely from full solves; the fast one solves the constraints with
 * constant rows as a banded block factorised once per active set, bordered
 * by the moving ones, in O(n + m).
 */
class ImplicitStepSystem
{
public:
  /// What a constraint does in the step.
  enum class Role : char
  {
    none,
    force,
    touching,
    engaged
  };

  /// The next BDF-2 step's history rho = f x_{n+1} + fp x_n, formed with the solution.
  struct NextHistory
  {
    const dealii::Vector<double>* q_n = nullptr;
    const dealii::Vector<double>* v_n = nullptr;
    double f = 0., fp = 0.;
  };

  ImplicitStepSystem(const SemiDiscreteSystem& system, double c) : system(system), c(c) {}
  virtual ~ImplicitStepSystem() = default;

  /// The BDF weight c of D_h x = c x - rho_x.
  double weight() const { return c; }

  /**
   * Starts a step to time @p t from the history @p rho_q, @p rho_v (kept by
   * reference until the step's last solve()), with the constraints' rows
   * @p rows at t. @p held (or nullptr) marks the constraints with constant
   * rows that held at every history point of a BDF-2 step: their eta and mu
   * vanish in exact arithmetic (the BDF weights sum to c), which an
   * implementation may use. With @p next, every solve() also forms the next
   * step's history (take_next_history()). @p continued: @p rho_q, @p rho_v
   * are what take_next_history() gave after the last solve (the
   * implementation may reuse what it derived from them).
   */
  virtual void start(const std::vector<ConstraintState>& rows, double t,
                     const dealii::Vector<double>& rho_q,
                     const dealii::Vector<double>& rho_v, const std::vector<bool>* held,
                     const NextHistory* next, bool continued) = 0;

  /**
   * Solves the step's system with the constraints in @p roles (one per
   * constraint): q, v, a and lambda (lambda_i = 0 where no force). Throws
   * SimulationError if the multiplier system is singular.
   */
  virtual void solve(const std::vector<Role>& roles, dealii::Vector<double>& q,
                     dealii::Vector<double>& v, dealii::Vector<double>& a,
                     std::vector<double>& lambda) = 0;

  /**
   * Swaps the next history that the last solve() formed into @p rho_q,
   * @p rho_v (for the next start(), continued).
   */
  virtual void take_next_history(dealii::Vector<double>& rho_q,
                                 dealii::Vector<double>& rho_v) = 0;

protected:
  /// Keeps the inputs of start() for the step's solves.
  void keep_step(const std::vector<ConstraintState>& step_rows, const double t,
                 const dealii::Vector<double>& step_rho_q,
                 const dealii::Vector<double>& step_rho_v, const NextHistory* next)
  {
    rows = &step_rows;
    time = t;
    rho_q = &step_rho_q;
    rho_v = &step_rho_v;
    with_next = next != nullptr;
    if (with_next)
      next_request = *next;
  }

  const SemiDiscreteSystem& system;
  const double c;
  /// The step's rows, time, history and next-history request (keep_step()).
  const std::vector<ConstraintState>* rows = nullptr;
  double time = 0.;
  const dealii::Vector<double>*rho_q = nullptr, *rho_v = nullptr;
  NextHistory next_request;
  bool with_next = false;
};

/**
 * The step system of weight @p c on @p system, done by @p algebra, with
 * @p solver for S (the fast implementation). @p forms_next_history: its
 * steps follow each other (BDF-2), so that forming the next history with
 * the solution pays.
 */
std::unique_ptr<ImplicitStepSystem>
make_implicit_step_system(const SemiDiscreteSystem& system, double c,
                          LinearAlgebra algebra, LinearSolverType solver,
                          bool forms_next_history);
} // namespace pantocat
