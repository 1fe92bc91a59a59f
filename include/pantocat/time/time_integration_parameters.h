#pragma once

#include <pantocat/lac/sparse_direct_solver.h>

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace pantocat
{
/**
 * Memory [bytes] a dynamic run keeps per time step: the contact-force series
 * (t, x_p, lambda_p and the contact flag of every step, for the zero-phase
 * low pass at the end) and its room to grow.
 */
constexpr double memory_per_step = 64.;

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
  unsigned int ida_maximum_order = 2; ///< of IDA's BDF formulas (1-5)
  /// IDA's sparse direct solver: sundials-klu | trilinos-klu | umfpack.
  std::string ida_linear_solver = "sundials-klu";
  unsigned int max_active_set_iterations = 20;

  static void declare_parameters(dealii::ParameterHandler& prm);
  void parse_parameters(dealii::ParameterHandler& prm);
  /**
   * Checks that a run of @p end_time seconds (@p run describes it for the
   * message) in steps of time_step can be made: its number of steps must be
   * finite and fit into memory, at memory_per_step bytes each (a dt of
   * 1e-300 s gave a step count beyond the range of the counter, which then
   * read 0 steps and reported the run completed); throws InputError.
   */
  void check_number_of_steps(double end_time, const std::string& run) const;

  /// The number of steps of a run of @p end_time seconds: ceil(t_e / time_step).
  unsigned long number_of_steps(double end_time) const;

  /**
   * The step a run of @p end_time seconds takes: t_e / number_of_steps(), so
   * that the last step ends exactly at t_e (the pantograph exactly at its
   * final position). Never larger than time_step; equal to it when it
   * divides t_e, otherwise shorter by less than time_step / n.
   */
  double step_for(double end_time) const;

private:
  /// ceil(t_e / time_step) as a double (it may exceed any integer type).
  double steps_of(double end_time) const;
};
} // namespace pantocat
