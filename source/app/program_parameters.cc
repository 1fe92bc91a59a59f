#include <pantocat/app/parameter_input.h>
#include <pantocat/app/program_parameters.h>
#include <pantocat/base/input_error.h>
#include <pantocat/simulation/checkpoint.h>

#include <deal.II/base/utilities.h>

#include <iostream>

namespace pantocat
{
bool is_sweep(const RunMode mode)
{
  return mode == RunMode::speed_sweep || mode == RunMode::parameter_sweep ||
         mode == RunMode::monte_carlo;
}

bool is_study(const RunMode mode)
{
  return mode == RunMode::convergence_study || mode == RunMode::work_precision ||
         is_sweep(mode);
}

void ProgramParameters::declare_parameters(dealii::ParameterHandler& prm,
                                           const unsigned int n_pantographs,
                                           const PantographCase& first_pantograph)
{
  prm.enter_subsection("Run");
  prm.declare_entry(
      "Mode", "dynamics",
      dealii::Patterns::Selection(
          "dynamics|static|eigenfrequencies|convergence study|work precision|speed "
          "sweep|parameter sweep|monte carlo"),
      "dynamics: the coupled pantograph-catenary run from x_p(0) to the final "
      "position (Sec. 6); static: the initial catenary under gravity, droppers "
      "and the contact load lambda_p(0) at x_p(0) (Fig. 5); eigenfrequencies: "
      "lowest and highest eigenfrequency of each wire (Table 1); convergence "
      "study, work precision: many dynamic runs (subsection Study), spread "
      "over MPI ranks under mpirun; speed sweep, parameter sweep, monte carlo: the "
      "contact-force statistics of the evaluation window for many dynamic runs "
      "(subsection Sweep), spread over MPI ranks by a work queue.");
  prm.declare_entry(
      "Start", "static equilibrium",
      dealii::Patterns::Selection("static equilibrium|paper"),
      "How a dynamic run with pantographs on the wire starts. static equilibrium: "
      "catenary and pantographs at rest in the static equilibrium of the whole system, "
      "each contact pressed with the force its pantograph exerts (its static plus "
      "aerodynamic force), each pantograph moving as one body with the wire under its "
      "contact point, as benchmark codes start; paper: the paper's start (13) with "
      "Pantograph/Initial contact force and Initial offset (the paper's 20 m cases).");
  prm.leave_subsection();
  prm.enter_subsection("Eigenfrequencies");
  prm.declare_entry("Discretisations", "fem, fdm",
                    dealii::Patterns::List(dealii::Patterns::Selection("fem|fdm"), 1),
                    "Space discretisations compared in eigenfrequency mode.");
  prm.leave_subsection();
  SceneParameters::declare_parameters(prm, n_pantographs, first_pantograph);
  CatenaryParameters::declare_parameters(prm);
  LineParameters::declare_parameters(prm);
  DiscretisationParameters::declare_parameters(prm);
  TimeIntegrationParameters::declare_parameters(prm);
  OutputParameters::declare_parameters(prm);
  StatisticsParameters::declare_parameters(prm);
  StudyParameters::declare_parameters(prm);
  SweepParameters::declare_parameters(prm);
  CheckpointParameters::declare_parameters(prm);
  GuardParameters::declare_parameters(prm);
  ElasticityParameters::declare_parameters(prm);
  AssessmentCriteria::declare_parameters(prm);
}

void ProgramParameters::parse_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Run");
  const std::string m = prm.get("Mode");
  mode = m == "eigenfrequencies"    ? RunMode::eigenfrequencies
         : m == "static"            ? RunMode::static_equilibrium
         : m == "convergence study" ? RunMode::convergence_study
         : m == "work precision"    ? RunMode::work_precision
         : m == "speed sweep"       ? RunMode::speed_sweep
         : m == "parameter sweep"   ? RunMode::parameter_sweep
         : m == "monte carlo"       ? RunMode::monte_carlo
                                    : RunMode::dynamics;
  const Start start =
      prm.get("Start") == "paper" ? Start::paper : Start::static_equilibrium;
  prm.leave_subsection();
  prm.enter_subsection("Eigenfrequencies");
  eigenfrequency_discretisations.clear();
  for (const auto& name :
       dealii::Utilities::split_string_list(prm.get("Discretisations")))
    eigenfrequency_discretisations.push_back(space_method_from_string(name));
  prm.leave_subsection();
  scene.parse_parameters(prm);
  scene.start = start;
  catenary.parse_parameters(prm);
  line.parse_parameters(prm);
  discretisation.parse_parameters(prm);
  time_integration.parse_parameters(prm);
  output.parse_parameters(prm);
  statistics.parse_parameters(prm);
  study.parse_parameters(prm);
  sweep.parse_parameters(prm, m);
  checkpoint.parse_parameters(prm);
  guards.parse_parameters(prm);
  elasticity.parse_parameters(prm);
  assessment.parse_parameters(prm);
  fingerprint = critical_parameters(prm);

  make_case().check();
  require(!line.is_line() || mode == RunMode::dynamics, "Run/Mode", m,
          "a line of " + std::to_string(line.n_sections) +
              " tension sections runs in Mode = dynamics; the static, eigenfrequency and "
              "study modes take one section (Line/Number of sections = 1)");
  require(!line.is_line() || output.vtu_interval == 0., "Output/VTU interval",
          output.vtu_interval,
          "the VTU frames show the wires of one section; allowed on a line of " +
              std::to_string(line.n_sections) + " sections: 0 (no frames)");
  if (is_study(mode)) // Study/Contact laws = penalty: Scene's law for every run
    make_case().check_contact_damping(study.penalty, "Scene/Contact damping");
  require(mode != RunMode::convergence_study || !study.all_combinations,
          "Study/Refinements", "all combinations",
          "a convergence study pairs N+1 and dt row by row and prints the observed "
          "order between successive rows; allowed: paired (all combinations is for "
          "Mode = work precision)");
  if (is_study(mode))
    require(scene.pantographs[0].has_body() && scene.contact_wire == WireModel::elastic,
            "Scene/Pantograph", scene.pantographs[0].model,
            "studies and sweeps measure the contact force lambda_p on the elastic wire: "
            "allowed "
            "two-mass | three-mass | mass-chain with Contact wire = elastic");
  elasticity.check(catenary.number_of_spans());
  require(
      !elasticity.enabled() || scene.droppers != DropperModel::bilateral,
      "Elasticity/Span", elasticity.span,
      "the static check lets the droppers slacken, which Scene/Droppers = "
      "bilateral forbids; allowed 0 (off) with it, or Droppers = unilateral or elastic");
  checkpoint.check(time_integration.integrator);
  output.check(time_integration.time_step, catenary.length());
  statistics.check(time_integration.time_step, pantograph().initial_position,
                   pantograph().final_position,
                   make_case().window_supports(statistics.window_section));
  if (mode == RunMode::dynamics)
    make_case().check_dynamics();
}

Case ProgramParameters::make_case() const
{
  Case c{scene, catenary, discretisation, time_integration, guards};
  c.line = line;
  return c;
}

StudyCase ProgramParameters::make_study_case() const
{
  StudyCase s;
  static_cast<Case&>(s) = make_case();
  s.study = study;
  s.statistics = statistics;
  s.output.directory = output.directory;
  s.output.plots = output.plots;
  return s;
}

void read_program_parameters(dealii::ParameterHandler& prm, const std::string& file,
                             const std::vector<std::string>& overrides)
{
  // Pass 1: how many pantographs, and pantograph 1's values (entries of
  // further pantographs are not declared yet and are skipped).
  dealii::ParameterHandler first_pass;
  ProgramParameters::declare_parameters(first_pass);
  read_parameter_file(first_pass, file, overrides, true);
  CatenaryParameters::move_old_names(first_pass, std::cerr);
  const unsigned int n = SceneParameters::number_of_pantographs(first_pass);
  first_pass.enter_subsection("Scene");
  first_pass.set("Number of pantographs", "1");
  first_pass.leave_subsection();
  SceneParameters scene;
  scene.parse_parameters(first_pass);
  ProgramParameters::declare_parameters(prm, n, scene.pantographs[0]);
  read_parameter_file(prm, file, overrides);
  CatenaryParameters::move_old_names(prm, std::cerr);
}
} // namespace pantocat
