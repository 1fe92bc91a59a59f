#pragma once

#include <pantocat/catenary/catenary_parameters.h>
#include <pantocat/io/output_parameters.h>
#include <pantocat/pantograph/pantograph_parameters.h>
#include <pantocat/scene/scene_parameters.h>
#include <pantocat/simulation/checkpoint_parameters.h>
#include <pantocat/simulation/guard_parameters.h>
#include <pantocat/simulation/statistics_parameters.h>
#include <pantocat/space/discretisation_parameters.h>
#include <pantocat/studies/study_parameters.h>
#include <pantocat/time/time_integration_parameters.h>

#include <deal.II/base/parameter_handler.h>

#include <vector>

namespace pantocat
{
/// What a run computes.
enum class RunMode
{
  static_equilibrium, ///< the initial catenary of Sec. 2.2 / Fig. 5
  eigenfrequencies,   ///< Table 1 of Sec. 6
  dynamics,           ///< the coupled run of Sec. 6 (Figs. 6, 7)
  convergence_study,  ///< one case for a list of refinements: errors and orders
  work_precision      ///< error against CPU time for several methods
};

/// All parameters of one run: one struct per prm subsection.
struct ProgramParameters
{
  RunMode mode = RunMode::static_equilibrium;
  std::vector<SpaceMethod> eigenfrequency_discretisations = {SpaceMethod::fem,
                                                             SpaceMethod::fdm};
  SceneParameters scene;
  CatenaryParameters catenary;
  PantographParameters pantograph;
  DiscretisationParameters discretisation;
  TimeIntegrationParameters time_integration;
  OutputParameters output;
  StatisticsParameters statistics;
  StudyParameters study;
  CheckpointParameters checkpoint;
  GuardParameters guards;
  /// The parameters a checkpoint of this run must agree with (critical_parameters()).
  ParameterFingerprint fingerprint;

  static void declare_parameters(dealii::ParameterHandler& prm);
  /// Reads every subsection and cross-checks them; throws InputError.
  void parse_parameters(dealii::ParameterHandler& prm);
};
} // namespace pantocat
