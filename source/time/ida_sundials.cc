#include <pantocat/base/input_error.h>
#include <pantocat/time/ida_sundials.h>

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
} // namespace

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
} // namespace pantocat
