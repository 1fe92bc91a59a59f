#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>
#include <pantocat/space/discretisation_parameters.h>

#include <sstream>

namespace pantocat
{
const char* to_string(const SpaceMethod method)
{
  return method == SpaceMethod::fem ? "fem" : "fdm";
}

SpaceMethod space_method_from_string(const std::string& name)
{
  require(name == "fem" || name == "fdm", "Discretisation/Method", name,
          "allowed: fem | fdm");
  return name == "fem" ? SpaceMethod::fem : SpaceMethod::fdm;
}

void DiscretisationParameters::declare_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Discretisation");
  prm.declare_entry("Method", "fem", dealii::Patterns::Selection("fem|fdm"),
                    "fem: linear Lagrange carrier and C1 cubic Hermite contact wire "
                    "(Sec. 4.2); fdm: second-order finite differences (Sec. 4.3).");
  prm.declare_entry("Messenger element", "linear Lagrange",
                    dealii::Patterns::Selection("linear Lagrange|cubic Hermite"),
                    "FEM element of the carrier: linear Lagrange for the string of the "
                    "paper (Sec. 4.2); cubic Hermite (C1, as the contact wire) for a "
                    "carrier with bending stiffness (Scene/Messenger bending).");
  prm.declare_alias("Messenger element", "Carrier element", true);
  prm.declare_entry("Number of intervals", "500", dealii::Patterns::Integer(2),
                    "N + 1: number of cells of the equidistant grid of each wire.");
  prm.declare_entry("Load shape", "smoothed delta",
                    dealii::Patterns::Selection("smoothed delta|point"),
                    "Distribution of the contact force: the C1 cubic spline delta_eps of "
                    "(25), or a point load (15)/(16).");
  prm.declare_entry("Load half-width", "0.2", dealii::Patterns::Double(0.),
                    "epsilon [m]: delta_eps vanishes outside [-epsilon, epsilon].");
  prm.leave_subsection();
}

void DiscretisationParameters::parse_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Discretisation");
  method = space_method_from_string(prm.get("Method"));
  n_intervals = prm.get_integer("Number of intervals");
  carrier_element = prm.get("Messenger element") == "cubic Hermite"
                        ? CarrierElement::cubic_hermite
                        : CarrierElement::linear_lagrange;
  load_shape =
      prm.get("Load shape") == "point" ? LoadShape::point : LoadShape::smoothed_delta;
  load_half_width = prm.get_double("Load half-width");
  prm.leave_subsection();
}

double estimated_memory_bytes(const unsigned int n_intervals)
{
  return memory_per_interval * n_intervals;
}

void DiscretisationParameters::check(const double span) const
{
  require(n_intervals >= 2, "Discretisation/Number of intervals", n_intervals,
          "must be >= 2");
  check_memory();
  if (load_shape == LoadShape::smoothed_delta)
    require(load_half_width > 0. && 2. * load_half_width < span,
            "Discretisation/Load half-width", load_half_width,
            "must lie in (0, L/2) = (0, " + number_to_string(span / 2.) + ")");
}
void DiscretisationParameters::check_memory() const
{
  const double available = physical_memory_bytes();
  const double needed = estimated_memory_bytes(n_intervals);
  if (available == 0. || needed <= available)
    return;
  std::ostringstream message;
  message.precision(3);
  message << "a run on this grid needs about " << needed / 1e9
          << " GB of memory (estimate: " << memory_per_interval / 1e3
          << " kB per interval), more than the " << available / 1e9
          << " GB this machine has; choose at most "
          << static_cast<unsigned long>(available / memory_per_interval) << " intervals";
  require(false, "Discretisation/Number of intervals", n_intervals, message.str());
}
} // namespace pantocat
