#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>
#include <pantocat/pantograph/pantograph_parameters.h>

#include <deal.II/base/utilities.h>

namespace pantocat
{
using dealii::Patterns::Double;

void PantographParameters::declare_parameters(dealii::ParameterHandler& prm,
                                              const std::string& subsection,
                                              const PantographParameters& defaults)
{
  prm.enter_subsection(subsection);
  prm.declare_entry("Initial position", number_to_string(defaults.initial_position),
                    Double(), "x_p(0) [m], inside (epsilon, L - epsilon).");
  prm.declare_entry("Final position", number_to_string(defaults.final_position), Double(),
                    "The run stops when x_p reaches this position [m] (with several "
                    "pantographs: when the first of them reaches its final position).");
  prm.declare_entry("Speed", number_to_string(defaults.speed), Double(),
                    "Pantograph speed v_p [m/s], > 0.");
  prm.declare_entry("Initial contact force",
                    number_to_string(defaults.initial_contact_force), Double(0.),
                    "lambda_p(0) [N]: the contact load of the initial static catenary.");
  prm.declare_entry("Initial offset", number_to_string(defaults.initial_offset), Double(),
                    "w_p1(0) - w_p2(0) [m]: 0 in (13); 0.002 at 48 m/s (Sec. 6).");
  prm.enter_subsection("Two-mass model");
  const TwoMassPantographParameters& d = defaults.two_mass;
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
  prm.enter_subsection("Three-mass model");
  const ThreeMassPantographParameters& t = defaults.three_mass;
  const auto list = [](const std::array<double, 3>& a)
  {
    return number_to_string(a[0]) + ", " + number_to_string(a[1]) + ", " +
           number_to_string(a[2]);
  };
  const dealii::Patterns::List three(Double(0.), 3, 3);
  prm.declare_entry("Masses", list(t.masses), three,
                    "m_1, m_2, m_3 [kg]: head, upper frame, lower frame.");
  prm.declare_entry("Stiffnesses", list(t.stiffnesses), three,
                    "c_1, c_2, c_3 [N/m]: head-upper, upper-lower, lower-ground.");
  prm.declare_entry("Dampings", list(t.dampings), three,
                    "d_1, d_2, d_3 [N s/m]: head-upper, upper-lower, lower-ground.");
  prm.declare_entry("Uplift force", number_to_string(t.uplift_force), Double(),
                    "Static uplift force F_0 on body 3 [N].");
  prm.leave_subsection();
  prm.leave_subsection();
}

void PantographParameters::declare_parameters(dealii::ParameterHandler& prm)
{
  declare_parameters(prm, "Pantograph", PantographParameters());
}

void PantographParameters::parse_parameters(dealii::ParameterHandler& prm,
                                            const std::string& subsection_name)
{
  subsection = subsection_name;
  prm.enter_subsection(subsection);
  initial_position = prm.get_double("Initial position");
  final_position = prm.get_double("Final position");
  speed = prm.get_double("Speed");
  initial_contact_force = prm.get_double("Initial contact force");
  initial_offset = prm.get_double("Initial offset");
  prm.enter_subsection("Two-mass model");
  two_mass.head_mass = prm.get_double("Head mass");
  two_mass.frame_mass = prm.get_double("Frame mass");
  two_mass.head_stiffness = prm.get_double("Head stiffness");
  two_mass.frame_stiffness = prm.get_double("Frame stiffness");
  two_mass.head_damping = prm.get_double("Head damping");
  two_mass.frame_damping = prm.get_double("Frame damping");
  two_mass.uplift_force = prm.get_double("Uplift force");
  prm.leave_subsection();
  prm.enter_subsection("Three-mass model");
  const auto read = [&](const std::string& name, std::array<double, 3>& a)
  {
    const auto values = dealii::Utilities::string_to_double(
        dealii::Utilities::split_string_list(prm.get(name)));
    std::copy(values.begin(), values.end(), a.begin());
  };
  read("Masses", three_mass.masses);
  read("Stiffnesses", three_mass.stiffnesses);
  read("Dampings", three_mass.dampings);
  three_mass.uplift_force = prm.get_double("Uplift force");
  prm.leave_subsection();
  prm.leave_subsection();
}

void PantographParameters::check(const double span, const double eps) const
{
  const std::string range =
      "(" + number_to_string(eps) + ", " + number_to_string(span - eps) + ")";
  require(speed > 0., subsection + "/Speed", speed, "must be > 0");
  require(initial_position > eps && initial_position < span - eps,
          subsection + "/Initial position", initial_position,
          "the contact area must lie inside the span: allowed " + range);
  require(final_position > initial_position && final_position < span - eps,
          subsection + "/Final position", final_position,
          "must lie in (Initial position, L - epsilon) = (" +
              number_to_string(initial_position) + ", " + number_to_string(span - eps) +
              ")");
  require(two_mass.head_mass > 0., subsection + "/Two-mass model/Head mass",
          two_mass.head_mass, "must be > 0");
  require(two_mass.frame_mass > 0., subsection + "/Two-mass model/Frame mass",
          two_mass.frame_mass, "must be > 0");
  for (unsigned int i = 0; i < 3; ++i)
    require(three_mass.masses[i] > 0., subsection + "/Three-mass model/Masses",
            three_mass.masses[i], "every mass must be > 0");
}
} // namespace pantocat
