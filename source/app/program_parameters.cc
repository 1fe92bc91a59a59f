#include <pantocat/app/program_parameters.h>
#include <pantocat/base/input_error.h>
#include <pantocat/simulation/checkpoint.h>

#include <deal.II/base/utilities.h>

#include <sstream>

namespace pantocat
{
namespace
{
/**
 * What a dynamic run needs beyond each subsection's own checks, before any
 * output is touched: unknowns to integrate (create_time_integrator refuses
 * an empty system too, for any caller), and a number of steps that is finite
 * and fits into memory.
 */
void check_dynamic_run(const ProgramParameters& p)
{
  const SceneParameters& scene = p.scene;
  require(scene.carrier == WireModel::elastic ||
              scene.contact_wire == WireModel::elastic || scene.has_pantograph_body(),
          "Scene/Pantograph", to_string(scene.pantograph),
          "with Carrier = rigid and Contact wire = rigid the scene has no unknowns, "
          "nothing to integrate in time; make a wire elastic or choose two-mass | "
          "three-mass");
  const PantographParameters& pantograph = p.pantograph;
  std::ostringstream run;
  run << "the run from x_p = " << pantograph.initial_position << " to "
      << pantograph.final_position << " m at v_p = " << pantograph.speed << " m/s ("
      << pantograph.end_time() << " s)";
  p.time_integration.check_number_of_steps(pantograph.end_time(), run.str());
}
} // namespace

void ProgramParameters::declare_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Run");
  prm.declare_entry(
      "Mode", "dynamics",
      dealii::Patterns::Selection(
          "dynamics|static|eigenfrequencies|convergence study|work precision"),
      "dynamics: the coupled pantograph-catenary run from x_p(0) to the final "
      "position (Sec. 6); static: the initial catenary under gravity, droppers "
      "and the contact load lambda_p(0) at x_p(0) (Fig. 5); eigenfrequencies: "
      "lowest and highest eigenfrequency of each wire (Table 1); convergence "
      "study, work precision: many dynamic runs (subsection Study), spread "
      "over MPI ranks under mpirun.");
  prm.leave_subsection();
  prm.enter_subsection("Eigenfrequencies");
  prm.declare_entry("Discretisations", "fem, fdm",
                    dealii::Patterns::List(dealii::Patterns::Selection("fem|fdm"), 1),
                    "Space discretisations compared in eigenfrequency mode.");
  prm.leave_subsection();
  SceneParameters::declare_parameters(prm);
  CatenaryParameters::declare_parameters(prm);
  PantographParameters::declare_parameters(prm);
  DiscretisationParameters::declare_parameters(prm);
  TimeIntegrationParameters::declare_parameters(prm);
  OutputParameters::declare_parameters(prm);
  StatisticsParameters::declare_parameters(prm);
  StudyParameters::declare_parameters(prm);
  CheckpointParameters::declare_parameters(prm);
  GuardParameters::declare_parameters(prm);
}

void ProgramParameters::parse_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Run");
  const std::string m = prm.get("Mode");
  mode = m == "eigenfrequencies"    ? RunMode::eigenfrequencies
         : m == "static"            ? RunMode::static_equilibrium
         : m == "convergence study" ? RunMode::convergence_study
         : m == "work precision"    ? RunMode::work_precision
                                    : RunMode::dynamics;
  prm.leave_subsection();
  prm.enter_subsection("Eigenfrequencies");
  eigenfrequency_discretisations.clear();
  for (const auto& name :
       dealii::Utilities::split_string_list(prm.get("Discretisations")))
    eigenfrequency_discretisations.push_back(space_method_from_string(name));
  prm.leave_subsection();
  scene.parse_parameters(prm);
  catenary.parse_parameters(prm);
  pantograph.parse_parameters(prm);
  discretisation.parse_parameters(prm);
  time_integration.parse_parameters(prm);
  output.parse_parameters(prm);
  statistics.parse_parameters(prm);
  study.parse_parameters(prm);
  checkpoint.parse_parameters(prm);
  guards.parse_parameters(prm);
  fingerprint = critical_parameters(prm);

  scene.check();
  if (scene.carrier_bending && scene.carrier == WireModel::elastic)
  {
    require(catenary.carrier.bending_stiffness > 0., "Catenary/Carrier/Bending stiffness",
            catenary.carrier.bending_stiffness, "must be > 0 with Scene/Carrier bending");
    require(discretisation.method == SpaceMethod::fdm ||
                discretisation.carrier_element == CarrierElement::cubic_hermite,
            "Discretisation/Carrier element", "linear Lagrange",
            "C0 elements have no bending energy: Scene/Carrier bending needs cubic "
            "Hermite (or Method = fdm)");
  }
  if (mode == RunMode::convergence_study || mode == RunMode::work_precision)
    require(scene.has_pantograph_body() && scene.contact_wire == WireModel::elastic,
            "Scene/Pantograph", to_string(scene.pantograph),
            "studies measure the contact force lambda_p on the elastic wire: allowed "
            "two-mass | three-mass with Contact wire = elastic");
  discretisation.check(catenary.span);
  pantograph.check(catenary.span, discretisation.load_shape == LoadShape::smoothed_delta
                                      ? discretisation.load_half_width
                                      : 0.);
  checkpoint.check(time_integration.integrator);
  output.check(time_integration.time_step);
  statistics.check(time_integration.time_step, pantograph.initial_position,
                   pantograph.final_position);
  if (mode == RunMode::dynamics)
    check_dynamic_run(*this);
}
} // namespace pantocat
