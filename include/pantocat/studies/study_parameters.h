#pragma once

#include <pantocat/space/discretisation_parameters.h>
#include <pantocat/system/constraint.h>
#include <pantocat/time/time_integration_parameters.h>

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace pantocat
{
/// What the errors of a study are measured against.
enum class StudyReference
{
  finest_run,  ///< the last (finest) entry of the refinement lists, per method
  separate_run ///< one extra run with its own discretisation, N+1 and dt
};

/**
 * The "Study" subsection: the runs of a convergence study or a work-precision
 * study. The refinement lists are paired entry by entry (N+1_k, dt_k); a list
 * with one entry (or none: the case's own value) is used for every k; or
 * (Refinements = all combinations) every N+1 runs with every dt. Every
 * combination of a discretisation, an integrator and a contact law runs the
 * whole list.
 */
struct StudyParameters
{
  std::vector<unsigned int> n_intervals;    ///< N+1 per refinement; empty: the case's
  std::vector<double> time_steps;           ///< dt per refinement [s]; empty: the case's
  std::vector<SpaceMethod> discretisations; ///< empty: the case's
  std::vector<std::string> integrators;     ///< empty: the case's
  /// Contact laws of the pantographs (unilateral | bilateral | penalty); empty: the
  /// case's.
  std::vector<std::string> contact_laws;
  /// k_c and c_c of Contact laws = penalty (Scene/Contact stiffness, Contact damping).
  Compliance penalty;
  /// Every N+1 with every dt (work precision) instead of entry by entry.
  bool all_combinations = false;
  StudyReference reference = StudyReference::finest_run;
  SpaceMethod reference_discretisation = SpaceMethod::fem;
  std::string reference_integrator = "bdf2";
  unsigned int reference_n_intervals = 1000;
  double reference_time_step = 1e-5;
  /// The error table (lambda_p over time against the reference, and the wire
  /// and eigenfrequency errors if asked): Quantities lists one of them.
  bool error_table = true;
  bool wire_errors = true;           ///< contact wire at t_e in L2 and H1
  bool eigenfrequency_errors = true; ///< lowest eigenfrequency of each wire
  /// Contact statistics of every run and their successive differences (no reference).
  bool contact_statistics = false;
  double target_relative_error = 0.01;
  std::string output_name; ///< file base name; empty: convergence | work_precision

  static void declare_parameters(dealii::ParameterHandler& prm);
  void parse_parameters(dealii::ParameterHandler& prm);

private:
  /// Scene/Contact stiffness and damping when Contact laws lists penalty.
  void parse_penalty(dealii::ParameterHandler& prm);
};
} // namespace pantocat
