#pragma once

#include <pantocat/analysis/elasticity_parameters.h>
#include <pantocat/catenary/catenary_parameters.h>
#include <pantocat/catenary/line_parameters.h>
#include <pantocat/io/output_parameters.h>
#include <pantocat/scene/scene_parameters.h>
#include <pantocat/simulation/assessment.h>
#include <pantocat/simulation/case.h>
#include <pantocat/simulation/checkpoint_parameters.h>
#include <pantocat/simulation/guard_parameters.h>
#include <pantocat/simulation/statistics_parameters.h>
#include <pantocat/space/discretisation_parameters.h>
#include <pantocat/studies/study_case.h>
#include <pantocat/studies/study_parameters.h>
#include <pantocat/studies/sweep_parameters.h>
#include <pantocat/time/time_integration_parameters.h>

#include <deal.II/base/parameter_handler.h>

#include <map>
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
  work_precision,     ///< error against CPU time for several methods
  speed_sweep,        ///< the window's statistics for a list of speeds
  parameter_sweep,    ///< the window's statistics over one or two prm entries
  monte_carlo         ///< the window's statistics over random installation deviations
};

/// True for the modes whose runs are spread over MPI ranks (studies and sweeps).
bool is_study(RunMode mode);
/// True for speed sweep, parameter sweep and monte carlo.
bool is_sweep(RunMode mode);

/// All parameters of one run: one struct per prm subsection.
struct ProgramParameters
{
  RunMode mode = RunMode::static_equilibrium;
  std::vector<SpaceMethod> eigenfrequency_discretisations = {SpaceMethod::fem,
                                                             SpaceMethod::fdm};
  SceneParameters scene; ///< with every pantograph (subsections Pantograph, Pantograph k)
  CatenaryParameters catenary;
  LineParameters line;
  DiscretisationParameters discretisation;
  TimeIntegrationParameters time_integration;
  OutputParameters output;
  StatisticsParameters statistics;
  StudyParameters study;
  SweepParameters sweep; ///< speed sweep, parameter sweep, monte carlo
  CheckpointParameters checkpoint;
  GuardParameters guards;
  ElasticityParameters elasticity; ///< the static check (Mode = static)
  AssessmentCriteria assessment;   ///< the criteria of the window's assessment
  /// The entries the case file and --set gave, "Subsection/Name" -> value
  /// (entries_set(); the others keep their defaults): summary.json's inputs.
  std::map<std::string, std::string> inputs;
  /// The parameters a checkpoint of this run must agree with (critical_parameters()).
  ParameterFingerprint fingerprint;

  /**
   * Declares every entry; subsections Pantograph 2 .. Pantograph
   * @p n_pantographs with the values of @p first_pantograph as defaults.
   */
  static void declare_parameters(dealii::ParameterHandler& prm,
                                 unsigned int n_pantographs = 1,
                                 const PantographCase& first_pantograph = {});
  /// Reads every subsection and cross-checks them; throws InputError.
  void parse_parameters(dealii::ParameterHandler& prm);

  /// The case these parameters describe: physics and numerics, no output settings.
  Case make_case() const;
  /// The case of a study mode with the study's parameters and outputs.
  StudyCase make_study_case() const;
  /// Pantograph 1 (subsection Pantograph).
  const PantographParameters& pantograph() const
  {
    return scene.pantographs[0].parameters;
  }
  PantographParameters& pantograph() { return scene.pantographs[0].parameters; }
};
/**
 * Reads @p file and the command-line @p overrides into @p prm (empty), in two
 * passes: the first finds Scene/Number of pantographs and pantograph 1's
 * values, the second declares Pantograph 2 .. n with those as defaults and
 * reads strictly. Throws InputError with one line.
 */
void read_program_parameters(dealii::ParameterHandler& prm, const std::string& file,
                             const std::vector<std::string>& overrides);
} // namespace pantocat
