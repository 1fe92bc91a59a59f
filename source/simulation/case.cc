#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>
#include <pantocat/simulation/case.h>

#include <deal.II/base/exceptions.h>

#include <limits>
#include <sstream>

namespace pantocat
{
bool InstallationDeviations::any() const
{
  return !dropper_lengths.empty() || !steady_arm_heights.empty() ||
         carrier_tension_factor != 1. || contact_wire_tension_factor != 1.;
}

void InstallationDeviations::apply(CatenaryParameters& c) const
{
  if (!any())
    return;
  Assert(dropper_lengths.empty() || dropper_lengths.size() == c.n_droppers(),
         dealii::ExcDimensionMismatch(dropper_lengths.size(), c.n_droppers()));
  for (unsigned int j = 0; j < dropper_lengths.size(); ++j)
    c.dropper_lengths[j] += dropper_lengths[j];
  const std::size_t n_arms = c.steady_arm_positions().size();
  Assert(steady_arm_heights.empty() || steady_arm_heights.size() == n_arms,
         dealii::ExcDimensionMismatch(steady_arm_heights.size(), n_arms));
  if (!steady_arm_heights.empty())
    c.steady_arm_preloads.resize(n_arms, 0.);
  for (std::size_t k = 0; k < steady_arm_heights.size(); ++k)
    c.steady_arm_preloads[k] += c.steady_arm_stiffness * steady_arm_heights[k];
  c.carrier.tension *= carrier_tension_factor;
  c.contact_wire.tension *= contact_wire_tension_factor;
  try
  {
    c.check(); // what a prm file may not give, installation may not give either
  }
  catch (const InputError& e)
  {
    throw InputError(std::string("the catenary as installed (with its installation "
                                 "deviations) is refused: ") +
                     e.what());
  }
}

double Case::end_time() const
{
  double t = std::numeric_limits<double>::infinity();
  for (const PantographCase& p : scene.pantographs)
    if (!p.is_absent())
      t = std::min(t, p.parameters.end_time());
  return t < std::numeric_limits<double>::infinity()
             ? t
             : scene.pantographs.front().parameters.end_time();
}

void Case::check() const
{
  scene.check();
  line.check(catenary);
  check_line();
  if (scene.carrier_bending && scene.carrier == WireModel::elastic)
  {
    require(catenary.carrier.bending_stiffness > 0.,
            "Catenary/Messenger/Bending stiffness", catenary.carrier.bending_stiffness,
            "must be > 0 with Scene/Messenger bending");
    require(discretisation.method == SpaceMethod::fdm ||
                discretisation.carrier_element == CarrierElement::cubic_hermite,
            "Discretisation/Messenger element", "linear Lagrange",
            "C0 elements have no bending energy: Scene/Messenger bending needs cubic "
            "Hermite (or Method = fdm)");
  }
  // k_d = 0 would be Compliance{0}, a rigid dropper: refused, not reinterpreted.
  require(scene.droppers != DropperModel::elastic || catenary.dropper_stiffness > 0.,
          "Catenary/Droppers/Stiffness", catenary.dropper_stiffness,
          "must be > 0 with Scene/Droppers = elastic (the tension-only spring k_d; "
          "rigid droppers are Droppers = unilateral or bilateral)");
  discretisation.check(catenary.length());
  const double eps = discretisation.load_shape == LoadShape::smoothed_delta
                         ? discretisation.load_half_width
                         : 0.;
  scene.check_spacing(line_length(), eps);
  for (const PantographCase& p : scene.pantographs)
  {
    p.parameters.check(line_length(), eps);
    check_speed_ramp(p.parameters);
    check_contact_damping(p.contact_compliance, p.contact_entry("Contact damping"));
  }
}

std::vector<double> Case::window_supports(const unsigned int section) const
{
  require(section >= 1 && section <= line.n_sections, "Statistics/Window section",
          section,
          "sections run from 1 to " + std::to_string(line.n_sections) +
              " (Line/Number of sections)");
  const CatenaryParameters c = sections()[section - 1];
  std::vector<double> x = c.support_positions();
  for (double& s : x)
    s += c.start;
  return x;
}

void Case::check_line() const
{
  if (!line.is_line())
    return;
  const std::string n = std::to_string(line.n_sections);
  for (const PantographCase& p : scene.pantographs)
    require(!p.is_moving_force(), "Scene/Pantograph", "moving force",
            "a line of " + n +
                " sections has two contact wires in each overlap, and a moving force "
                "on one wire has no law to share itself; allowed: a pantograph model, "
                "or Line/Number of sections = 1");
  require(scene.contact_wire == WireModel::elastic && scene.carrier == WireModel::elastic,
          "Scene/Contact wire",
          scene.contact_wire == WireModel::elastic ? "elastic" : "rigid",
          "a line of " + n +
              " sections needs elastic wires (a rigid wire has no "
              "sections); allowed: elastic, or Line/Number of sections = 1");
  require(!installation.any(), "Mode", "monte carlo",
          "installation deviations are drawn for one section; allowed on a line of 1 "
          "section");
}

void Case::check_contact_damping(const Compliance& law,
                                 const std::string& parameter) const
{
  if (law.stiffness == 0.)
    return; // rigid: no damping
  // In contact, lambda = -k_c g - c_c dg/dt: the spring acts on the time
  // scale c_c / k_c of the damper. Beyond the run the contact is a damper
  // only, and the implicit methods' rows g + (c_c / k_c) dg/dt lose the gap
  // in round-off (the active set then cycles); c_c <= k_c t_e keeps
  // (c_c / k_c) / dt below the number of steps.
  const double t_e = end_time(), largest = law.stiffness * t_e;
  require(law.damping <= largest, parameter, law.damping,
          "the relaxation time c_c / k_c of the penalty contact must not exceed the run "
          "(t_e = " +
              number_to_string(t_e) + " s); allowed: 0 <= c_c <= k_c t_e = " +
              number_to_string(largest) + " N s/m");
}

void Case::check_speed_ramp(const PantographParameters& p) const
{
  // The acceleration v_p / T_r acts from t = 0 to T_r: a ramp shorter than a
  // step is not resolved (1e-300 s would make it 1e302 m/s^2, and the step
  // maps overflow).
  const double dt = time_integration.time_step;
  require(p.speed_ramp == 0. || p.speed_ramp >= dt, p.subsection + "/Speed ramp",
          p.speed_ramp,
          "the ramp from rest to v_p must last at least one time step, or be 0 (no "
          "ramp): its acceleration v_p / T_r = " +
              number_to_string(p.speed / p.speed_ramp) +
              " m/s^2 is not resolved by steps of " + number_to_string(dt) +
              " s; allowed: 0 or >= Time integration/Time step = " +
              number_to_string(dt) + " s");
}

void Case::check_dynamics() const
{
  require(scene.carrier == WireModel::elastic ||
              scene.contact_wire == WireModel::elastic || scene.has_pantograph_body(),
          "Scene/Pantograph", scene.pantographs[0].model,
          "with Messenger = rigid and Contact wire = rigid the scene has no unknowns, "
          "nothing to integrate in time; make a wire elastic or choose two-mass | "
          "three-mass | mass-chain");
  const PantographParameters& p = scene.pantographs[0].parameters;
  std::ostringstream run;
  run << "the run from x_p = " << p.initial_position << " to " << p.final_position
      << " m at v_p = " << p.speed << " m/s";
  if (p.speed_ramp > 0.)
    run << " after a speed ramp of " << p.speed_ramp << " s";
  run << " (" << end_time() << " s)";
  time_integration.check_number_of_steps(end_time(), run.str());
}
} // namespace pantocat
