#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>
#include <pantocat/simulation/case.h>

#include <deal.II/base/exceptions.h>

#include <limits>
#include <sstream>

namespace pantocat
{
namespace
{
/// t at which @p p reaches its final position.
double arrival_time(const PantographParameters& p)
{
  return (p.final_position - p.initial_position) / p.speed;
}
} // namespace

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
      t = std::min(t, arrival_time(p.parameters));
  return t < std::numeric_limits<double>::infinity()
             ? t
             : arrival_time(scene.pantographs.front().parameters);
}

void Case::check() const
{
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
  discretisation.check(catenary.length());
  const double eps = discretisation.load_shape == LoadShape::smoothed_delta
                         ? discretisation.load_half_width
                         : 0.;
  scene.check_spacing(catenary.length(), eps);
  for (const PantographCase& p : scene.pantographs)
    p.parameters.check(catenary.length(), eps);
}

void Case::check_dynamics() const
{
  require(scene.carrier == WireModel::elastic ||
              scene.contact_wire == WireModel::elastic || scene.has_pantograph_body(),
          "Scene/Pantograph", scene.pantographs[0].model,
          "with Carrier = rigid and Contact wire = rigid the scene has no unknowns, "
          "nothing to integrate in time; make a wire elastic or choose two-mass | "
          "three-mass | mass-chain");
  const PantographParameters& p = scene.pantographs[0].parameters;
  std::ostringstream run;
  run << "the run from x_p = " << p.initial_position << " to " << p.final_position
      << " m at v_p = " << p.speed << " m/s (" << end_time() << " s)";
  time_integration.check_number_of_steps(end_time(), run.str());
}
} // namespace pantocat
