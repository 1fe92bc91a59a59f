#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>
#include <pantocat/pantograph/pantograph_parameters.h>

namespace pantocat
{
using dealii::Patterns::Double;

void PantographParameters::declare_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Pantograph");
  prm.declare_entry("Model", "two-mass", dealii::Patterns::Selection("two-mass"),
                    "Lumped-mass pantograph model: two-mass = Eq. (12).");
  prm.declare_entry("Initial position", "2", Double(),
                    "x_p(0) [m], inside (epsilon, L - epsilon).");
  prm.declare_entry("Final position", "18", Double(),
                    "The run stops when x_p reaches this position [m].");
  prm.declare_entry("Speed", "32", Double(), "Pantograph speed v_p [m/s], > 0.");
  prm.declare_entry("Initial contact force", "8.75", Double(0.),
                    "lambda_p(0) [N]: the contact load of the initial static catenary.");
  prm.declare_entry("Initial offset", "0", Double(),
                    "w_p1(0) - w_p2(0) [m]: 0 in (13); 0.002 at 48 m/s (Sec. 6).");
  prm.declare_entry("Constraints", "unilateral",
                    dealii::Patterns::Selection("unilateral|bilateral"),
                    "unilateral: droppers and contact may slacken (Sec. 5.3, the "
                    "paper's model); bilateral: they are equations (4), (32) at all "
                    "times (a smooth case, e.g. for convergence orders in time).");
  prm.enter_subsection("Two-mass model");
  const TwoMassPantographParameters d;
  prm.declare_entry("Head mass", number_to_string(d.head_mass), Double(0.), "m_1 [kg].");
  prm.declare_entry("Frame mass", number_to_string(d.frame_mass), Double(0.),
                    "m_2 [kg].");
  prm.declare_entry("Head stiffness", number_to_string(d.head_stiffness), Double(0.),
                    "c_1 [N/m].");
  prm.declare_entry("Frame stiffness", number_to_string(d.frame_stiffness), Double(0.),
                    "c_2 [N/m].");
  prm.declare_entry("Head damping", number_to_string(d.head_damping), Double(0.),
                    "d_1 [N s/m].");
  prm.declare_entry("Frame damping", number_to_string(d.frame_damping), Double(0.),
                    "d_2 [N s/m].");
  prm.declare_entry("Uplift force", number_to_string(d.uplift_force), Double(),
                    "Static uplift force F_0 on body 2 [N].");
  prm.leave_subsection();
  prm.leave_subsection();
}

void PantographParameters::parse_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Pantograph");
  model = prm.get("Model");
  initial_position = prm.get_double("Initial position");
  final_position = prm.get_double("Final position");
  speed = prm.get_double("Speed");
  initial_contact_force = prm.get_double("Initial contact force");
  initial_offset = prm.get_double("Initial offset");
  bilateral_constraints = prm.get("Constraints") == "bilateral";
  prm.enter_subsection("Two-mass model");
  two_mass.head_mass = prm.get_double("Head mass");
  two_mass.frame_mass = prm.get_double("Frame mass");
  two_mass.head_stiffness = prm.get_double("Head stiffness");
  two_mass.frame_stiffness = prm.get_double("Frame stiffness");
  two_mass.head_damping = prm.get_double("Head damping");
  two_mass.frame_damping = prm.get_double("Frame damping");
  two_mass.uplift_force = prm.get_double("Uplift force");
  prm.leave_subsection();
  prm.leave_subsection();
}

void PantographParameters::check(const double span, const double eps) const
{
  const std::string range =
      "(" + number_to_string(eps) + ", " + number_to_string(span - eps) + ")";
  require(speed > 0., "Pantograph/Speed", speed, "must be > 0");
  require(initial_position > eps && initial_position < span - eps,
          "Pantograph/Initial position", initial_position,
          "the contact area must lie inside the span: allowed " + range);
  require(final_position > initial_position && final_position < span - eps,
          "Pantograph/Final position", final_position,
          "must lie in (Initial position, L - epsilon) = (" +
              number_to_string(initial_position) + ", " + number_to_string(span - eps) +
              ")");
  require(two_mass.head_mass > 0., "Pantograph/Two-mass model/Head mass",
          two_mass.head_mass, "must be > 0");
  require(two_mass.frame_mass > 0., "Pantograph/Two-mass model/Frame mass",
          two_mass.frame_mass, "must be > 0");
}
} // namespace pantocat
