#pragma once

#include <pantocat/lac/sparse_direct_solver.h>

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace pantocat
{
struct TimeIntegrationParameters
{
  /// Name of the integrator (registered_integrators()): half-explicit, bdf2, ...
  std::string integrator = "half-explicit";
  double time_step = 5e-5;      ///< Delta t [s]
  bool force_step_size = false; ///< run an explicit method above its stability limit
  double rho_infinity = 0.5;    ///< generalized-alpha: spectral radius at infinity
  LinearSolverType linear_solver = LinearSolverType::banded; ///< implicit integrators
  double ida_relative_tolerance = 1e-6;
  double ida_absolute_tolerance = 1e-8;
  /// IDA's sparse direct solver: sundials-klu | trilinos-klu | umfpack.
  std::string ida_linear_solver = "sundials-klu";
  unsigned int max_active_set_iterations = 20;

  static void declare_parameters(dealii::ParameterHandler& prm);
  void parse_parameters(dealii::ParameterHandler& prm);
};
} // namespace pantocat
