#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>
#include <pantocat/catenary/catenary_parameters.h>

#include <deal.II/base/utilities.h>

#include <cmath>
#include <sstream>

namespace pantocat
{
using dealii::Patterns::Double;
using dealii::Patterns::List;

double WireParameters::wave_speed() const
{
  return std::sqrt(tension / mass_per_length);
}

double CatenaryParameters::clamp_load(const unsigned int j) const
{
  return (clamp_mass + 0.5 * dropper_lengths[j] * dropper_mass_per_length) * gravity;
}

namespace
{
std::string list_to_string(const std::vector<double>& values)
{
  std::ostringstream s;
  for (unsigned int i = 0; i < values.size(); ++i)
    s << (i ? ", " : "") << values[i];
  return s.str();
}

void declare_wire(dealii::ParameterHandler& prm, const WireParameters& defaults,
                  const bool beam)
{
  prm.declare_entry("Mass per length", number_to_string(defaults.mass_per_length),
                    Double(0.), "rho A [kg/m], > 0.");
  prm.declare_entry("Tension", number_to_string(defaults.tension), Double(0.),
                    "Tensile force T [N], > 0.");
  prm.declare_entry("Bending stiffness", number_to_string(defaults.bending_stiffness),
                    Double(0.),
                    beam ? "E I [N m^2], >= 0 (Euler-Bernoulli beam)."
                         : "E I [N m^2], >= 0: used only with Scene/Carrier bending = "
                           "true (the paper's carrier is a string).");
  prm.declare_entry("Damping", number_to_string(defaults.damping), Double(0.),
                    "Viscous damping beta [N s/m^2], >= 0.");
}

void parse_wire(dealii::ParameterHandler& prm, WireParameters& wire)
{
  wire.mass_per_length = prm.get_double("Mass per length");
  wire.tension = prm.get_double("Tension");
  wire.bending_stiffness = prm.get_double("Bending stiffness");
  wire.damping = prm.get_double("Damping");
}
} // namespace

void CatenaryParameters::declare_parameters(dealii::ParameterHandler& prm)
{
  const CatenaryParameters d;
  prm.enter_subsection("Catenary");
  prm.declare_entry("Span", "20", Double(0.), "Length L of the span [m] (Sec. 2.2).");
  prm.declare_entry("Support height", "1", Double(),
                    "Height l_c of the carrier above the contact wire at x = 0 and x = L "
                    "[m], boundary condition (3).");
  prm.declare_entry("Gravity", "9.81", Double(0.),
                    "Gravitational acceleration g [m/s^2].");
  prm.enter_subsection("Carrier");
  declare_wire(prm, d.carrier, false);
  prm.leave_subsection();
  prm.enter_subsection("Contact wire");
  declare_wire(prm, d.contact_wire, true);
  prm.leave_subsection();
  prm.enter_subsection("Droppers");
  prm.declare_entry(
      "Positions", list_to_string(d.dropper_positions), List(Double()),
      "Dropper positions x_d [m], a comma-separated list, each inside (0, L).");
  prm.declare_entry("Lengths", list_to_string(d.dropper_lengths), List(Double(0.)),
                    "Dropper lengths l_j [m], one per position.");
  prm.declare_entry("Mass per length", "0.14", Double(0.), "rho_d A_d [kg/m].");
  prm.declare_entry("Clamp mass", "0.25", Double(0.),
                    "Mass m_s of a suspension clamp [kg], Eq. (4).");
  prm.leave_subsection();
  prm.leave_subsection();
}

void CatenaryParameters::parse_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Catenary");
  span = prm.get_double("Span");
  support_height = prm.get_double("Support height");
  gravity = prm.get_double("Gravity");
  prm.enter_subsection("Carrier");
  parse_wire(prm, carrier);
  prm.leave_subsection();
  prm.enter_subsection("Contact wire");
  parse_wire(prm, contact_wire);
  prm.leave_subsection();
  prm.enter_subsection("Droppers");
  dropper_positions = dealii::Utilities::string_to_double(
      dealii::Utilities::split_string_list(prm.get("Positions")));
  dropper_lengths = dealii::Utilities::string_to_double(
      dealii::Utilities::split_string_list(prm.get("Lengths")));
  dropper_mass_per_length = prm.get_double("Mass per length");
  clamp_mass = prm.get_double("Clamp mass");
  prm.leave_subsection();
  prm.leave_subsection();
  check();
}

void CatenaryParameters::check() const
{
  require(span > 0., "Catenary/Span", span, "must be > 0");
  require(carrier.mass_per_length > 0., "Catenary/Carrier/Mass per length",
          carrier.mass_per_length, "must be > 0");
  require(carrier.tension > 0., "Catenary/Carrier/Tension", carrier.tension,
          "must be > 0");
  require(contact_wire.mass_per_length > 0., "Catenary/Contact wire/Mass per length",
          contact_wire.mass_per_length, "must be > 0");
  require(contact_wire.tension > 0. || contact_wire.bending_stiffness > 0.,
          "Catenary/Contact wire/Tension", contact_wire.tension,
          "tension and bending stiffness must not both be 0");
  require(dropper_lengths.size() == dropper_positions.size(), "Catenary/Droppers/Lengths",
          list_to_string(dropper_lengths),
          "needs one length per dropper position (" +
              std::to_string(dropper_positions.size()) + " positions given)");
  for (unsigned int j = 0; j < dropper_positions.size(); ++j)
  {
    const double x = dropper_positions[j];
    require(x > 0. && x < span, "Catenary/Droppers/Positions", x,
            "dropper positions must lie inside (0, Span) = (0, " +
                number_to_string(span) + ")");
    if (j > 0)
      require(x > dropper_positions[j - 1], "Catenary/Droppers/Positions",
              list_to_string(dropper_positions), "positions must be strictly increasing");
    require(dropper_lengths[j] > 0., "Catenary/Droppers/Lengths", dropper_lengths[j],
            "must be > 0");
  }
}
} // namespace pantocat
