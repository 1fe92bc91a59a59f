#pragma once

#include <pantocat/system/pattern_operators.h>
#include <pantocat/time/ida_integrator.h>

#include <idas/idas.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <string>
#include <utility>
#include <vector>

namespace pantocat
{
/**
 * IDA's smallest step, relative to the output step dt. A step this small
 * (5e-13 s at dt = 5e-5 s) resolves no physics of the catenary; IDA gets
 * there only where the problem is not smooth enough for it (a point load
 * crossing a node: its row jumps), and kept shrinking the step to 1e-20 s,
 * below the round-off of t, for minutes.
 */
inline constexpr double min_step_per_output_step = 1e-8;

/// IDA's internal steps per output step dt (one call of IDASolve); normal
/// runs take a few.
inline constexpr long max_steps_per_output_step = 500;

/// Events (restarts) per output step: more means that constraints chatter
/// without IDA getting on.
inline constexpr unsigned int max_events_per_output_step = 100;

/// A SUNDIALS linear solver on SparseDirectSolver (UMFPACK or Trilinos KLU).
SUNLinearSolver make_dealii_solver(LinearSolverType type, SUNContext context);

/// Why IDASolve returned @p flag, in words (@p h_min: IDA's smallest step).
std::string ida_failure_reason(int flag, double h_min);

/// Keeps SUNDIALS' last error message in the std::string @p data (instead of
/// printing it on stderr).
void keep_error_message(int, const char*, const char*, char* message, void* data);

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
} // namespace pantocat
