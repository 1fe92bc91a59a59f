#include <pantocat/base/input_error.h>
#include <pantocat/system/pattern_operators.h>
#include <pantocat/time/active_set.h>
#include <pantocat/time/ida_integrator.h>

#include <idas/idas.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace pantocat
{
namespace
{
/**
 * A SUNDIALS linear solver on the project's SparseDirectSolver (UMFPACK or
 * Trilinos Amesos KLU): setup copies IDA's sparse Jacobian (CSC) into a
 * deal.II matrix, rebuilding the pattern when the moving contact changed it,
 * and factorises; solve applies the factorisation. Exceptions do not cross
 * the C callbacks: they become a failure code, which IDA reports.
 */
struct DealiiDirectSolver
{
  LinearSolverType type;
  dealii::SparsityPattern pattern;
  dealii::SparseMatrix<double> matrix;
  std::vector<sunindextype> last_pattern;
  SparseDirectSolver solver;
  dealii::Vector<double> x;

  static SUNLinearSolver_Type get_type(SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; }
  static int setup(SUNLinearSolver S, SUNMatrix A)
  {
    auto& d = *static_cast<DealiiDirectSolver*>(S->content);
    try
    {
      const sunindextype n = SM_COLUMNS_S(A);
      const sunindextype* start = SM_INDEXPTRS_S(A);
      const sunindextype* row = SM_INDEXVALS_S(A);
      const double* value = SM_DATA_S(A);
      std::vector<sunindextype> now(start, start + n + 1);
      now.insert(now.end(), row, row + start[n]);
      if (now != d.last_pattern)
      {
        dealii::DynamicSparsityPattern dsp(n, n);
        for (sunindextype j = 0; j < n; ++j)
          for (sunindextype e = start[j]; e < start[j + 1]; ++e)
            dsp.add(row[e], j);
        d.matrix.clear();
        d.pattern.copy_from(dsp);
        d.matrix.reinit(d.pattern);
        d.last_pattern.swap(now);
        d.x.reinit(n);
      }
      d.matrix = 0.;
      for (sunindextype j = 0; j < n; ++j)
        for (sunindextype e = start[j]; e < start[j + 1]; ++e)
          d.matrix.set(row[e], j, value[e]);
      d.solver.factorize(d.matrix, "IDA Jacobian", d.type);
      return 0;
    }
    catch (...)
    {
      return SUNLS_PACKAGE_FAIL_UNREC;
    }
  }
  static int solve(SUNLinearSolver S, SUNMatrix, N_Vector x, N_Vector b, realtype)
  {
    auto& d = *static_cast<DealiiDirectSolver*>(S->content);
    try
    {
      const double* bb = N_VGetArrayPointer(b);
      std::copy(bb, bb + d.x.size(), d.x.begin());
      d.solver.solve(d.x);
      std::copy(d.x.begin(), d.x.end(), N_VGetArrayPointer(x));
      return 0;
    }
    catch (...)
    {
      return SUNLS_PACKAGE_FAIL_UNREC;
    }
  }
  static int free(SUNLinearSolver S)
  {
    delete static_cast<DealiiDirectSolver*>(S->content);
    S->content = nullptr;
    SUNLinSolFreeEmpty(S);
    return 0;
  }
};

/**
 * IDA's smallest step, relative to the output step dt. A step this small
 * (5e-13 s at dt = 5e-5 s) resolves no physics of the catenary; IDA gets
 * there only where the problem is not smooth enough for it (a point load
 * crossing a node: its row jumps), and kept shrinking the step to 1e-20 s,
 * below the round-off of t, for minutes.
 */
constexpr double min_step_per_output_step = 1e-8;

/// IDA's internal steps per output step dt (one call of IDASolve); normal
/// runs take a few.
constexpr long max_steps_per_output_step = 500;

/// Events (restarts) per output step: more means that constraints chatter
/// without IDA getting on.
constexpr unsigned int max_events_per_output_step = 100;

/// Why IDASolve returned @p flag, in words.
std::string ida_failure_reason(const int flag, const double h_min)
{
  std::ostringstream reason;
  reason << std::setprecision(3);
  switch (flag)
  {
  case IDA_TOO_MUCH_WORK:
    reason << "more than " << max_steps_per_output_step
           << " internal steps in one output step";
    break;
  case IDA_ERR_FAIL:
    reason << "the error test failed repeatedly, or with the step at its minimum "
           << h_min << " s";
    break;
  case IDA_CONV_FAIL:
    reason << "the Newton iteration did not converge, repeatedly or with the step at "
              "its minimum "
           << h_min << " s";
    break;
  default:
    reason << "IDASolve failed";
  }
  reason << " (" << IDAGetReturnFlagName(flag) << ')';
  return reason.str();
}

/// Keeps SUNDIALS' last error message (instead of printing it on stderr).
void keep_error_message(int, const char*, const char*, char* message, void* data)
{
  *static_cast<std::string*>(data) = message;
}

SUNLinearSolver make_dealii_solver(LinearSolverType type, SUNContext context)
{
  SUNLinearSolver S = SUNLinSolNewEmpty(context);
  S->content = new DealiiDirectSolver{type, {}, {}, {}, {}, {}};
  S->ops->gettype = DealiiDirectSolver::get_type;
  S->ops->setup = DealiiDirectSolver::setup;
  S->ops->solve = DealiiDirectSolver::solve;
  S->ops->free = DealiiDirectSolver::free;
  return S;
}
/// The mass matrix M of the projections at events.
ConstrainedOperator::Definition mass_matrix()
{
  ConstrainedOperator::Definition M;
  M.what = "mass matrix M";
  return M;
}
} // namespace

/// SUNDIALS objects and the callbacks of IDA (residual, Jacobian, roots).
struct IdaIntegrator::Sundials
{
  explicit Sundials(IdaIntegrator& owner) : owner(owner), operators(owner.system)
  {
    if (SUNContext_Create(nullptr, &context) != 0)
      throw SimulationError("IDA: cannot create a SUNDIALS context");
    const sunindextype size = 2 * owner.n + 2 * owner.m;
    y = N_VNew_Serial(size, context);
    yp = N_VNew_Serial(size, context);
    id = N_VNew_Serial(size, context);
    tolerances = N_VNew_Serial(size, context);
    double* flags = N_VGetArrayPointer(id);
    for (sunindextype i = 0; i < size; ++i)
      flags[i] =
          i < 2 * static_cast<sunindextype>(owner.n) ? 1. : 0.; // q, v differential
    // Non-zeros: M, D, K twice each (at most), constraint rows and their
    // transposes, the identity of inactive multipliers.
    const auto& sys = owner.system;
    nnz = 4 * sys.sparsity->n_nonzero_elements() + 2 * size;
    J = SUNSparseMatrix(size, size, nnz, CSC_MAT, context);
    solver = owner.linear_solver == IdaLinearSolver::sundials_klu
                 ? SUNLinSol_KLU(y, J, context)
                 : make_dealii_solver(owner.linear_solver == IdaLinearSolver::umfpack
                                          ? LinearSolverType::umfpack
                                          : LinearSolverType::trilinos_klu,
                                      context);
    memory = IDACreate(context);
  }
  ~Sundials()
  {
    IDAFree(&memory);
    SUNLinSolFree(solver);
    SUNMatDestroy(J);
    N_VDestroy(y);
    N_VDestroy(yp);
    N_VDestroy(id);
    N_VDestroy(tolerances);
    SUNContext_Free(&context);
  }

  static int residual(realtype t, N_Vector yy, N_Vector yyp, N_Vector rr, void* data);
  static int jacobian(realtype t, realtype cj, N_Vector yy, N_Vector yyp, N_Vector rr,
                      SUNMatrix Jac, void* data, N_Vector, N_Vector, N_Vector);
  static int roots(realtype t, N_Vector yy, N_Vector yyp, realtype* gout, void* data);

  /// The Jacobian's columns (CSC, per column the rows and values).
  using Columns = std::vector<std::vector<std::pair<unsigned int, double>>>;
  /// The entries of compliant constraint @p k: F_v by lambda, its force law
  /// (if @p engaged) by q, v and lambda, and mu = 0.
  void add_compliant_columns(unsigned int k, const ConstraintState& c, bool engaged,
                             Columns& column) const;
  /// The entries of M, D, K (with cj of IDA's derivative).
  void add_matrix_columns(double cj, Columns& column) const;
  /// The entries of the constraints' rows at @p c (by the active set).
  void add_constraint_columns(const std::vector<ConstraintState>& c,
                              Columns& column) const;
  /// @p column into the CSC matrix @p Jac; a new pattern re-analysed (KLU).
  void write_columns(Columns& column, SUNMatrix Jac);

  IdaIntegrator& owner;
  SUNContext context = nullptr;
  N_Vector y = nullptr, yp = nullptr, id = nullptr, tolerances = nullptr;
  SUNMatrix J = nullptr;
  SUNLinearSolver solver = nullptr;
  void* memory = nullptr;
  sunindextype nnz = 0;
  std::string last_error;            ///< SUNDIALS' message of its last error
  std::vector<sunindextype> pattern; ///< of the last Jacobian (column starts, rows)
  PatternOperators operators;        ///< M, D, K, f for the residual's pass
};

int IdaIntegrator::Sundials::residual(realtype t, N_Vector yy, N_Vector yyp, N_Vector rr,
                                      void* data)
{
  IdaIntegrator& I = static_cast<Sundials*>(data)->owner;
  const unsigned int n = I.n, m = I.m;
  const double *y = N_VGetArrayPointer(yy), *yp = N_VGetArrayPointer(yyp);
  double* r = N_VGetArrayPointer(rr);
  const double *q = y, *v = y + n, *lambda = y + 2 * n, *mu = y + 2 * n + m;
  const double *qp = yp, *vp = yp + n;
  const auto& c = I.rows.at(t, 1);
  const Sundials& S = *static_cast<Sundials*>(data);
  // F_q = M (q' - v), F_v = M v' + D v + K q - f: one pass over the shared pattern.
  S.operators.set_time(t);
  S.operators.motion(q, v, qp, vp, r, r + n);
  // - G^T mu, - G^T lambda and the constraints.
  for (unsigned int k = 0; k < m; ++k)
    if (I.system.constraints[k]->is_compliant())
    {
      // A force: F_v -= G^T lambda, lambda = max(0, -k g - c dg/dt) by its
      // branch: the linear law while engaged, 0 while not; the roots switch
      // the branch (roots()), so that IDA integrates a smooth system.
      double* r_v = r + n;
      c[k].G.add_transpose_to(r_v, -lambda[k]);
      r[2 * n + k] = lambda[k];
      if (I.active[k])
        r[2 * n + k] -= I.system.constraints[k]->trial_force(
            c[k].position_residual(q), c[k].velocity_residual(q, v));
      r[2 * n + m + k] = mu[k];
    }
    else if (I.active[k])
    {
      c[k].G.add_transpose_to(r, -mu[k]); // F_q -= G^T mu
      double* r_v = r + n;
      c[k].G.add_transpose_to(r_v, -lambda[k]); // F_v -= G^T lambda
      r[2 * n + k] = c[k].velocity_residual(q, v);
      r[2 * n + m + k] = c[k].position_residual(q);
    }
    else
    {
      r[2 * n + k] = lambda[k];
      r[2 * n + m + k] = mu[k];
    }
  return 0;
}

int IdaIntegrator::Sundials::jacobian(realtype t, realtype cj, N_Vector, N_Vector,
                                      N_Vector, SUNMatrix Jac, void* data, N_Vector,
                                      N_Vector, N_Vector)
{
  Sundials& S = *static_cast<Sundials*>(data);
  IdaIntegrator& I = S.owner;
  // Columns of J = dF/dy + cj dF/dy' (CSC).
  Columns column(2 * I.n + 2 * I.m);
  S.add_matrix_columns(cj, column);
  S.add_constraint_columns(I.rows.at(t, 1), column);
  S.write_columns(column, Jac);
  return 0;
}

void IdaIntegrator::Sundials::add_matrix_columns(const double cj, Columns& column) const
{
  const unsigned int n = owner.n;
  const SemiDiscreteSystem& sys = owner.system;
  // M, D, K are symmetric: column j = row j.
  for (unsigned int j = 0; j < n; ++j)
  {
    for (auto it = sys.mass.begin(j); it != sys.mass.end(j); ++it)
    {
      column[j].push_back({it->column(), cj * it->value()});         // F_q by q
      column[n + j].push_back({it->column(), -it->value()});         // F_q by v
      column[n + j].push_back({n + it->column(), cj * it->value()}); // F_v by v
    }
    for (auto it = sys.damping.begin(j); it != sys.damping.end(j); ++it)
      column[n + j].push_back({n + it->column(), it->value()});
    for (auto it = sys.stiffness.begin(j); it != sys.stiffness.end(j); ++it)
      column[j].push_back({n + it->column(), it->value()});
  }
}

void IdaIntegrator::Sundials::add_constraint_columns(
    const std::vector<ConstraintState>& c, Columns& column) const
{
  const unsigned int n = owner.n, m = owner.m;
  for (unsigned int k = 0; k < m; ++k)
    if (owner.system.constraints[k]->is_compliant())
      add_compliant_columns(k, c[k], owner.active[k], column);
    else if (owner.active[k])
    {
      for (std::size_t e = 0; e < c[k].G.size(); ++e)
      {
        const unsigned int i = c[k].G.index[e];
        const double g = c[k].G.value[e];
        column[2 * n + k].push_back({n + i, -g}); // F_v by lambda
        column[2 * n + m + k].push_back({i, -g}); // F_q by mu
        column[n + i].push_back({2 * n + k, g});  // velocity constraint by v
        column[i].push_back({2 * n + m + k, g});  // position constraint by q
      }
      for (std::size_t e = 0; e < c[k].G_t.size(); ++e)
        column[c[k].G_t.index[e]].push_back({2 * n + k, c[k].G_t.value[e]});
    }
    else
    {
      column[2 * n + k].push_back({2 * n + k, 1.});
      column[2 * n + m + k].push_back({2 * n + m + k, 1.});
    }
}

void IdaIntegrator::Sundials::write_columns(Columns& column, SUNMatrix Jac)
{
  sunindextype total = 0;
  for (auto& col : column)
  {
    std::sort(col.begin(), col.end());
    total += col.size();
  }
  if (total > SM_NNZ_S(Jac))
    SUNSparseMatrix_Reallocate(Jac, total);
  sunindextype* start = SM_INDEXPTRS_S(Jac);
  sunindextype* row = SM_INDEXVALS_S(Jac);
  double* value = SM_DATA_S(Jac);
  sunindextype e = 0;
  for (std::size_t j = 0; j < column.size(); ++j)
  {
    start[j] = e;
    for (std::size_t k = 0; k < column[j].size(); ++k)
    {
      // Merge repeated rows (several constraints on one unknown).
      if (k > 0 && column[j][k].first == column[j][k - 1].first)
      {
        value[e - 1] += column[j][k].second;
        continue;
      }
      row[e] = column[j][k].first;
      value[e] = column[j][k].second;
      ++e;
    }
  }
  start[column.size()] = e;
  // The moving contact row changes the pattern: KLU's numeric refactorisation
  // assumes the pattern of its symbolic analysis, so a new pattern needs a
  // new analysis (SUNLinSol_KLUReInit frees the factorisations).
  std::vector<sunindextype> new_pattern(start, start + column.size() + 1);
  new_pattern.insert(new_pattern.end(), row, row + e);
  if (new_pattern != pattern)
  {
    pattern.swap(new_pattern);
    if (owner.linear_solver == IdaLinearSolver::sundials_klu)
      SUNLinSol_KLUReInit(solver, Jac, SM_NNZ_S(Jac), SUNKLU_REINIT_PARTIAL);
  }
}

void IdaIntegrator::Sundials::add_compliant_columns(const unsigned int k,
                                                    const ConstraintState& c,
                                                    const bool engaged,
                                                    Columns& column) const
{
  const unsigned int n = owner.n, m = owner.m;
  const Compliance& law = owner.system.constraints[k]->compliance();
  for (std::size_t e = 0; e < c.G.size(); ++e)
  {
    const unsigned int i = c.G.index[e];
    const double g = c.G.value[e];
    column[2 * n + k].push_back({n + i, -g}); // F_v by lambda
    if (engaged)
    {
      // lambda + k g + c dg/dt = 0 by q and v.
      column[i].push_back({2 * n + k, law.stiffness * g});
      column[n + i].push_back({2 * n + k, law.damping * g});
    }
  }
  if (engaged)
    for (std::size_t e = 0; e < c.G_t.size(); ++e)
      column[c.G_t.index[e]].push_back({2 * n + k, law.damping * c.G_t.value[e]});
  column[2 * n + k].push_back({2 * n + k, 1.});
  column[2 * n + m + k].push_back({2 * n + m + k, 1.}); // mu = 0
}

double IdaIntegrator::compliant_root(const unsigned int k, const ConstraintState& c,
                                     const double* q, const double* v) const
{
  // Engaged iff h = max(g, g + (c/k) dg/dt) < 0 (g < 0 and -k g - c dg/dt > 0):
  // a disengaged spring engages when h falls through 0, an engaged one
  // releases when -h does.
  const Compliance& law = system.constraints[k]->compliance();
  const double g = c.position_residual(q);
  const double h =
      std::max(g, g + law.damping / law.stiffness * c.velocity_residual(q, v));
  return active[k] ? -h : h;
}

int IdaIntegrator::Sundials::roots(realtype t, N_Vector yy, N_Vector, realtype* gout,
                                   void* data)
{
  IdaIntegrator& I = static_cast<Sundials*>(data)->owner;
  const double* y = N_VGetArrayPointer(yy);
  const auto& c = I.rows.at(t, 1);
  for (unsigned int k = 0; k < I.m; ++k)
    if (!I.system.constraints[k]->is_unilateral())
      gout[k] = 1.; // never switches
    else if (I.system.constraints[k]->is_compliant())
      gout[k] = I.compliant_root(k, c[k], y, y + I.n);
    else if (I.active[k])
      gout[k] = y[2 * I.n + k]; // lambda: release when it falls through 0
    else
      gout[k] = c[k].position_residual(y); // gap: closes when it falls through 0
  return 0;
}

IdaIntegrator::IdaIntegrator(const SemiDiscreteSystem& system, const double output_step,
                             const double relative_tolerance,
                             const double absolute_tolerance,
                             const IdaLinearSolver solver, const LinearAlgebra algebra)
    : TimeIntegrator(system), dt(output_step), rtol(relative_tolerance),
      atol(absolute_tolerance), linear_solver(solver), n(system.n_dofs()),
      m(system.n_constraints()),
      M(make_constrained_operator(system, mass_matrix(), algebra)), rows(system),
      load_scratch(system.n_dofs())
{
  stats.events_localised = true;
}

IdaIntegrator::~IdaIntegrator() = default;

std::vector<unsigned int> IdaIntegrator::held_rigid(const std::vector<bool>& set) const
{
  std::vector<unsigned int> held;
  for (unsigned int k = 0; k < m; ++k)
    if (set[k] && !system.constraints[k]->is_compliant())
      held.push_back(k);
  return held;
}

void IdaIntegrator::accelerations(const double t, const std::vector<ConstraintState>& c,
                                  const std::vector<bool>& set,
                                  const dealii::Vector<double>& q,
                                  const dealii::Vector<double>& v,
                                  dealii::Vector<double>& a, std::vector<double>& lambda)
{
  // M a = f - K q - D v + G^T lambda of the compliant constraints (engaged as
  // in the set: at a root the toggled branch, the sign of the crossing), then
  // the rigid ones' lambda on acceleration level:
  // G a + 2 G_t v + G_tt q + z_tt = 0.
  system.load_at(t, a);
  system.stiffness.vmult(load_scratch, q);
  a -= load_scratch;
  system.damping.vmult(load_scratch, v);
  a -= load_scratch;
  std::vector<double> forces(m, 0.);
  for (unsigned int k = 0; k < m; ++k)
    if (set[k] && system.constraints[k]->is_compliant())
    {
      forces[k] = system.constraints[k]->trial_force(c[k].position_residual(q),
                                                     c[k].velocity_residual(q, v));
      c[k].G.add_transpose_to(a, forces[k]);
    }
  M->apply_inverse(a);
  M->project(
      held_rigid(set),
      [&](unsigned int k)
      { return c[k].G.dot(a) + 2. * c[k].G_t.dot(v) + c[k].G_tt.dot(q) + c[k].z_tt; },
      a, lambda, "IDA event");
  for (unsigned int k = 0; k < m; ++k)
    if (system.constraints[k]->is_compliant())
      lambda[k] = forces[k];
}

void IdaIntegrator::make_consistent(const double t, std::vector<bool> set)
{
  double* y = N_VGetArrayPointer(sun->y);
  double* yp = N_VGetArrayPointer(sun->yp);
  const auto& c = rows.at(t, 2);
  M->set_rows(c, t);
  dealii::Vector<double> q(n), v(n), a(n);
  std::copy(y, y + n, q.begin());
  std::copy(y + n, y + 2 * n, v.begin());
  std::vector<double> lambda(m, 0.), position_correction, impulse;
  bool closes = false;
  for (unsigned int k = 0; k < m; ++k)
    closes =
        closes || (set[k] && !active[k] && system.constraints[k]->is_rigid_unilateral());
  if (closes && pending_impulse.empty())
    pending_impulse.assign(m, 0.);
  std::vector<double> event_impulse(m, 0.);
  for (unsigned int round = 0; round <= m; ++round)
  {
    // Positions and velocities onto g = dg/dt = 0 (an inelastic impact where a
    // constraint closes; round-off elsewhere). v += M^-1 G^T P: P is the
    // impulse [N s].
    const std::vector<unsigned int> held = held_rigid(set);
    M->project(
        held, [&](unsigned int k) { return c[k].position_residual(q); }, q,
        position_correction, "IDA event");
    M->project(
        held, [&](unsigned int k) { return c[k].velocity_residual(q, v); }, v, impulse,
        "IDA event");
    if (closes)
      for (const unsigned int k : held)
      {
        pending_impulse[k] += impulse[k];
        event_impulse[k] += impulse[k];
      }
    accelerations(t, c, set, q, v, a, lambda);
    // A constraint that pulls separates: g'' > 0 without it.
    bool released = false;
    for (const unsigned int k : held)
      if (lambda[k] < 0. && system.constraints[k]->is_unilateral())
        set[k] = false, released = true;
    if (!released)
      break;
  }
  record_events(t, set, closes, event_impulse);
  std::copy(q.begin(), q.end(), y);
  std::copy(v.begin(), v.end(), y + n);
  for (unsigned int k = 0; k < m; ++k)
    y[2 * n + k] = lambda[k], y[2 * n + m + k] = 0.;
  std::copy(v.begin(), v.end(), yp);
  std::copy(a.begin(), a.end(), yp + n);
  std::fill(yp + 2 * n, yp + 2 * n + 2 * m, 0.);
}

void IdaIntegrator::record_events(const double t, const std::vector<bool>& set,
                                  const bool closes,
                                  const std::vector<double>& event_impulse)
{
  for (unsigned int k = 0; k < m; ++k)
    if (set[k] != active[k])
    {
      stats.localised_events.push_back(
          {t, k, set[k], set[k] && closes ? event_impulse[k] : 0.});
      ++stats.active_set_changes;
    }
  active = set;
}

void IdaIntegrator::initialize(const DynamicState& initial)
{
  sun = std::make_unique<Sundials>(*this);
  active = initial.active;
  // The compliant constraints' branch and force from the initial state.
  std::vector<double> initial_lambda = initial.lambda;
  const auto& c0 = rows.at(initial.t, 1);
  for (unsigned int k = 0; k < m; ++k)
    if (system.constraints[k]->is_compliant())
    {
      const Constraint& law = *system.constraints[k];
      const double g = c0[k].position_residual(initial.q),
                   rate = c0[k].velocity_residual(initial.q, initial.v);
      initial_lambda[k] = law.compliant_force(g, rate);
      active[k] = !law.is_unilateral() || (g < 0. && law.trial_force(g, rate) > 0.);
    }
  double* y = N_VGetArrayPointer(sun->y);
  double* yp = N_VGetArrayPointer(sun->yp);
  std::copy(initial.q.begin(), initial.q.end(), y);
  std::copy(initial.v.begin(), initial.v.end(), y + n);
  for (unsigned int k = 0; k < m; ++k)
    y[2 * n + k] = initial_lambda[k], y[2 * n + m + k] = 0.;
  std::copy(initial.v.begin(), initial.v.end(), yp);
  std::copy(initial.a.begin(), initial.a.end(), yp + n);
  std::fill(yp + 2 * n, yp + 2 * n + 2 * m, 0.);
  // Absolute tolerances: atol on q [m] and v [m/s]; the multipliers are
  // excluded from the error test (IDASetSuppressAlg) but weigh in IDA's Newton
  // convergence test, where a tolerance of atol on forces of ~100 N (lambda)
  // and on the GGL multiplier mu (~0) makes the test fail for no reason:
  // 1e-6 of their scale (1 N) there.
  double* tol = N_VGetArrayPointer(sun->tolerances);
  for (unsigned int i = 0; i < 2 * n + 2 * m; ++i)
    tol[i] = i < 2 * n ? atol : 1e-6;
  void* mem = sun->memory;
  bool ok = IDAInit(mem, Sundials::residual, initial.t, sun->y, sun->yp) == IDA_SUCCESS &&
            IDASetUserData(mem, sun.get()) == IDA_SUCCESS &&
            IDASVtolerances(mem, rtol, sun->tolerances) == IDA_SUCCESS &&
            IDASetId(mem, sun->id) == IDA_SUCCESS &&
            IDASetSuppressAlg(mem, SUNTRUE) == IDA_SUCCESS &&
            IDASetLinearSolver(mem, sun->solver, sun->J) == IDA_SUCCESS &&
            IDASetJacFn(mem, Sundials::jacobian) == IDA_SUCCESS &&
            IDARootInit(mem, m, Sundials::roots) == IDA_SUCCESS &&
            IDASetMaxNumSteps(mem, max_steps_per_output_step) == IDA_SUCCESS &&
            IDASetMinStep(mem, min_step_per_output_step * dt) == IDA_SUCCESS &&
            IDASetErrHandlerFn(mem, keep_error_message, &sun->last_error) == IDA_SUCCESS;
  std::vector<int> direction(m, -1); // gaps and forces falling through zero
  // (A scene without constraints has no roots: IDA refuses directions then.)
  ok = ok && (m == 0 || IDASetRootDirection(mem, direction.data()) == IDA_SUCCESS);
  if (!ok)
    throw SimulationError("IDA: the solver could not be set up");
  current = initial;
  current.impulse.clear();
  pending_impulse.clear();
  stats.localised_events.clear();
  counted.clear();
}

void IdaIntegrator::read_state(const double t)
{
  const double* y = N_VGetArrayPointer(sun->y);
  const double* yp = N_VGetArrayPointer(sun->yp);
  current.t = t;
  current.q.reinit(n, true);
  current.v.reinit(n, true);
  current.a.reinit(n, true);
  std::copy(y, y + n, current.q.begin());
  std::copy(y + n, y + 2 * n, current.v.begin());
  std::copy(yp + n, yp + 2 * n, current.a.begin());
  current.lambda.assign(y + 2 * n, y + 2 * n + m);
  clamp_compliant_forces(system, current.lambda);
  current.active = active;
  // The impacts located since the last output point are reported with it.
  current.impulse.swap(pending_impulse);
  pending_impulse.clear();
}

void IdaIntegrator::restart(const double t)
{
  collect_counters();
  counted = stats.counters; // IDAReInit resets IDA's counters
  if (IDAReInit(sun->memory, t, sun->y, sun->yp) != IDA_SUCCESS)
    throw SimulationError("IDA: restart after an event failed");
}

void IdaIntegrator::release_pulling_constraints(const double t)
{
  const double* lambda = N_VGetArrayPointer(sun->y) + 2 * n;
  std::vector<bool> set = active;
  bool pulls = false;
  for (unsigned int k = 0; k < m; ++k)
    if (active[k] && system.constraints[k]->is_rigid_unilateral() && lambda[k] < 0.)
      set[k] = false, pulls = true;
  if (!pulls)
    return;
  make_consistent(t, set);
  restart(t);
}

void IdaIntegrator::advance()
{
  const double t_out = current.t + dt;
  double t = current.t;
  unsigned int events = 0;
  while (t < t_out - 1e-14 * std::max(1., std::abs(t_out)))
  {
    const int flag = IDASolve(sun->memory, t_out, &t, sun->y, sun->yp, IDA_NORMAL);
    if (flag == IDA_ROOT_RETURN)
    {
      if (++events > max_events_per_output_step)
      {
        std::ostringstream s;
        s << "IDA failed at t = " << t << " s: more than " << max_events_per_output_step
          << " switches of the active set in the output step from " << current.t
          << " s (the constraints chatter)";
        throw SimulationError(s.str());
      }
      std::vector<int> found(m, 0);
      IDAGetRootInfo(sun->memory, found.data());
      std::vector<bool> set = active;
      for (unsigned int k = 0; k < m; ++k)
        if (found[k] != 0)
          set[k] = !active[k];
      make_consistent(t, set);
      restart(t);
      continue;
    }
    if (flag < 0)
    {
      std::ostringstream s;
      s << "IDA failed at t = " << t
        << " s: " << ida_failure_reason(flag, min_step_per_output_step * dt);
      if (!sun->last_error.empty())
        s << "; IDA: " << sun->last_error;
      throw SimulationError(s.str());
    }
  }
  release_pulling_constraints(t_out);
  // The derivative at t_out (IDA returns y' with y).
  read_state(t_out);
  ++stats.steps;
  collect_counters();
}

void IdaIntegrator::collect_counters()
{
  long steps = 0, residuals = 0, jacobians = 0, error_failures = 0,
       nonlinear_failures = 0, setups = 0, roots = 0;
  IDAGetNumSteps(sun->memory, &steps);
  IDAGetNumResEvals(sun->memory, &residuals);
  IDAGetNumJacEvals(sun->memory, &jacobians);
  IDAGetNumErrTestFails(sun->memory, &error_failures);
  IDAGetNumNonlinSolvConvFails(sun->memory, &nonlinear_failures);
  IDAGetNumLinSolvSetups(sun->memory, &setups);
  IDAGetNumGEvals(sun->memory, &roots);
  stats.counters = {{"ida_steps", steps},
                    {"residual_evaluations", residuals},
                    {"jacobian_evaluations", jacobians},
                    {"error_test_failures", error_failures},
                    {"nonlinear_convergence_failures", nonlinear_failures},
                    {"linear_solver_setups", setups},
                    {"root_function_evaluations", roots}};
  for (std::size_t i = 0; i < counted.size(); ++i)
    stats.counters[i].second += counted[i].second;
}

IntegratorEntry IdaIntegrator::registry_entry()
{
  IntegratorEntry e;
  e.name = "ida";
  e.description = "SUNDIALS IDA (variable order and step) on the GGL index-2 system, "
                  "events located by root finding";
  e.explicit_step_limit = false;
  e.writes_checkpoints = false;
  e.locates_events = true;
  e.create_with_linear_algebra = [](const SemiDiscreteSystem& system,
                                    const TimeIntegrationParameters& p,
                                    const LinearAlgebra algebra)
  {
    return std::make_unique<IdaIntegrator>(
        system, p.time_step, p.ida_relative_tolerance, p.ida_absolute_tolerance,
        p.ida_linear_solver == "umfpack"        ? IdaLinearSolver::umfpack
        : p.ida_linear_solver == "trilinos-klu" ? IdaLinearSolver::trilinos_klu
                                                : IdaLinearSolver::sundials_klu,
        algebra);
  };
  e.create = [make = e.create_with_linear_algebra](const SemiDiscreteSystem& system,
                                                   const TimeIntegrationParameters& p)
  { return make(system, p, LinearAlgebra::fast); };
  return e;
}
} // namespace pantocat
