#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>
#include <pantocat/pantograph/pantograph_parameters.h>

#include <deal.II/base/utilities.h>

#include <cmath>
#include <cstdlib>
#include <memory>

namespace pantocat
{
using dealii::Patterns::Double;

std::optional<double> speed_from_text(const std::string& text)
{
  const std::string trimmed = dealii::Utilities::trim(text);
  char* end = nullptr;
  const double value = std::strtod(trimmed.c_str(), &end);
  if (end == trimmed.c_str() || !std::isfinite(value))
    return std::nullopt;
  const std::string unit = dealii::Utilities::trim(std::string(end));
  if (unit.empty() || unit == "m/s")
    return value;
  if (unit == "km/h")
    return value / 3.6;
  return std::nullopt;
}

namespace
{
/// A speed as railway engineers give it: a number in m/s, or with its unit
/// ("88.9 m/s", "320 km/h").
class SpeedPattern : public dealii::Patterns::PatternBase
{
public:
  bool match(const std::string& text) const override
  {
    return speed_from_text(text).has_value();
  }
  std::string description(const OutputStyle = Machine) const override
  {
    return "[Speed: a number in m/s, or with its unit: 88.9 m/s, 320 km/h]";
  }
  std::unique_ptr<dealii::Patterns::PatternBase> clone() const override
  {
    return std::make_unique<SpeedPattern>();
  }
};
} // namespace

namespace
{

std::vector<double> read_list(dealii::ParameterHandler& prm, const std::string& name)
{
  return dealii::Utilities::string_to_double(
      dealii::Utilities::split_string_list(prm.get(name)));
}

const char* reference_name(const ChainReference r)
{
  return r == ChainReference::static_equilibrium ? "static equilibrium"
                                                 : "relaxed springs";
}

const char* start_name(const ChainStart s)
{
  return s == ChainStart::offset ? "offset" : "static equilibrium";
}
} // namespace

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
  prm.declare_entry("Speed", number_to_string(defaults.speed), SpeedPattern(),
                    "Pantograph speed v_p, > 0: in m/s, or with its unit (320 km/h).");
  prm.declare_entry("Speed ramp", number_to_string(defaults.speed_ramp), Double(0.),
                    "T_r [s]: the pantograph starts from rest and reaches v_p at the "
                    "constant acceleration v_p / T_r, over v_p T_r / 2 metres (a smooth "
                    "start away from an anchor); 0: at v_p from t = 0. The aerodynamic "
                    "force keeps its value at v_p. Allowed: 0, or at least one time "
                    "step. The run ends when x_p reaches Final position, T_r / 2 later "
                    "than at v_p throughout.");
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
  prm.declare_entry("Static force", number_to_string(d.uplift_force), Double(),
                    "Static contact force F_0 [N], on body 2 (the frame).");
  prm.declare_alias("Static force", "Uplift force", true);
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
  prm.declare_entry("Static force", number_to_string(t.uplift_force), Double(),
                    "Static contact force F_0 [N], on body 3 (the lower frame).");
  prm.declare_alias("Static force", "Uplift force", true);
  prm.leave_subsection();
  prm.enter_subsection("Mass-chain model");
  const MassChainPantographParameters& c = defaults.mass_chain;
  // Unbounded patterns: MassChainPantographParameters::check() refuses bad values
  // in one line naming the entry, the value and what is allowed.
  const dealii::Patterns::List numbers(Double(), 1, 1000);
  prm.declare_entry("Masses", list_to_string(c.masses), numbers,
                    "m_1, ..., m_n [kg], each > 0: head (body 1) first, frame (body n) "
                    "last. The number of values is the number of bodies n.");
  prm.declare_entry("Stiffnesses", list_to_string(c.stiffnesses), numbers,
                    "k_1, ..., k_n [N/m], each >= 0: k_i joins body i and body i + 1, "
                    "k_n joins the frame to the ground.");
  prm.declare_entry("Dampings", list_to_string(c.dampings), numbers,
                    "c_1, ..., c_n [N s/m], each >= 0, joining the bodies as the "
                    "stiffnesses. Every link needs k_i > 0 or c_i > 0.");
  prm.declare_entry("Static force", number_to_string(c.static_force), Double(),
                    "F_0 [N]: the net static uplift on the force body; the "
                    "pantograph's weight is part of it (no gravity acts on the "
                    "pantograph, as in (12)).");
  prm.declare_entry("Aerodynamic force a", number_to_string(c.aerodynamic_a), Double(),
                    "a [N] of the aerodynamic uplift F_a = a + b v_p^2, added to F_0 on "
                    "the force body.");
  prm.declare_entry("Aerodynamic force b", number_to_string(c.aerodynamic_b), Double(),
                    "b [N s^2/m^2] of the aerodynamic uplift F_a = a + b v_p^2 (v_p: "
                    "this pantograph's Speed).");
  prm.declare_entry("Force body", std::to_string(c.force_body),
                    dealii::Patterns::Integer(),
                    "The body (1 = head, ..., n = frame) that carries F_0 + F_a; 0 = "
                    "the frame, body n.");
  prm.declare_entry("Reference state", reference_name(c.reference),
                    dealii::Patterns::Selection("relaxed springs|static equilibrium"),
                    "What q = 0 means. relaxed springs: every spring at its unloaded "
                    "length, F_0 + F_a act on the force body (the paper's (12)); "
                    "static equilibrium: q = 0 is the static equilibrium under F_0 "
                    "with the head at z = 0 pressed by lambda_p = F_0, so the constant "
                    "load becomes F_0 on the head (plus F_a on the force body) and the "
                    "quasi-static contact force is F_0 + F_a - k_n w_pn (needs k_i > 0 "
                    "between the head and the force body).");
  prm.declare_entry("Initial configuration", start_name(c.start),
                    dealii::Patterns::Selection("static equilibrium|offset"),
                    "The consistent initial state. static equilibrium: the head on the "
                    "wire with lambda_p(0), bodies 1..n-1 in static balance (Initial "
                    "offset ignored); offset: the paper's choice (13) as for two-mass "
                    "and three-mass, w_p2 = w_p1 - Initial offset, the velocity of body "
                    "2 from the head equation (needs n >= 2 and c_1 > 0).");
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
  speed_ramp = prm.get_double("Speed ramp");
  speed = *speed_from_text(prm.get("Speed")); // the pattern has checked it
  initial_contact_force = prm.get_double("Initial contact force");
  initial_offset = prm.get_double("Initial offset");
  prm.enter_subsection("Two-mass model");
  two_mass.head_mass = prm.get_double("Head mass");
  two_mass.frame_mass = prm.get_double("Frame mass");
  two_mass.head_stiffness = prm.get_double("Head stiffness");
  two_mass.frame_stiffness = prm.get_double("Frame stiffness");
  two_mass.head_damping = prm.get_double("Head damping");
  two_mass.frame_damping = prm.get_double("Frame damping");
  two_mass.uplift_force = prm.get_double("Static force");
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
  three_mass.uplift_force = prm.get_double("Static force");
  prm.leave_subsection();
  prm.enter_subsection("Mass-chain model");
  mass_chain.masses = read_list(prm, "Masses");
  mass_chain.stiffnesses = read_list(prm, "Stiffnesses");
  mass_chain.dampings = read_list(prm, "Dampings");
  mass_chain.static_force = prm.get_double("Static force");
  mass_chain.aerodynamic_a = prm.get_double("Aerodynamic force a");
  mass_chain.aerodynamic_b = prm.get_double("Aerodynamic force b");
  mass_chain.force_body = prm.get_integer("Force body");
  mass_chain.reference = prm.get("Reference state") == "static equilibrium"
                             ? ChainReference::static_equilibrium
                             : ChainReference::relaxed_springs;
  mass_chain.start = prm.get("Initial configuration") == "offset"
                         ? ChainStart::offset
                         : ChainStart::static_equilibrium;
  prm.leave_subsection();
  prm.leave_subsection();
}

void MassChainPantographParameters::check(const std::string& subsection) const
{
  const std::string where = subsection + "/";
  const unsigned int n = n_bodies();
  const std::string count = "one value per mass, n = " + std::to_string(n);
  require(stiffnesses.size() == n, where + "Stiffnesses", list_to_string(stiffnesses),
          count + " (k_i joins body i and i + 1, k_n the frame and the ground)");
  require(dampings.size() == n, where + "Dampings", list_to_string(dampings),
          count + " (c_i joins body i and i + 1, c_n the frame and the ground)");
  for (unsigned int i = 0; i < n; ++i)
  {
    require(masses[i] > 0., where + "Masses", masses[i], "every mass must be > 0");
    require(stiffnesses[i] >= 0., where + "Stiffnesses", stiffnesses[i],
            "every stiffness must be >= 0");
    require(dampings[i] >= 0., where + "Dampings", dampings[i],
            "every damping must be >= 0");
  }
  require(stiffnesses[n - 1] > 0. || dampings[n - 1] > 0., where + "Dampings",
          list_to_string(dampings),
          "the chain is not tied to the ground (k_n = c_n = 0): its static state is "
          "singular; allowed: k_n > 0 or c_n > 0");
  for (unsigned int i = 0; i + 1 < n; ++i)
    require(stiffnesses[i] > 0. || dampings[i] > 0., where + "Dampings",
            list_to_string(dampings),
            "bodies " + std::to_string(i + 1) + " and " + std::to_string(i + 2) +
                " are not joined (k_" + std::to_string(i + 1) + " = c_" +
                std::to_string(i + 1) + " = 0); allowed: k_i > 0 or c_i > 0");
  require(force_body >= 0 && force_body <= static_cast<int>(n), where + "Force body",
          force_body,
          "allowed 0 (the frame) or 1.." + std::to_string(n) + " (body 1 = head)");
  if (reference == ChainReference::static_equilibrium)
    for (unsigned int i = 0; i + 1 < uplift_body(); ++i)
      require(stiffnesses[i] > 0., where + "Reference state", "static equilibrium",
              "the springs between the head and the force body carry F_0 statically: "
              "needs k_1..k_" +
                  std::to_string(uplift_body() - 1) + " > 0, but k_" +
                  std::to_string(i + 1) + " = 0");
  if (start == ChainStart::offset)
    require(n >= 2 && dampings[0] > 0., where + "Initial configuration", "offset",
            "solves the head equation for the velocity of body 2: needs at least two "
            "bodies and c_1 > 0; allowed otherwise: static equilibrium");
}

void PantographParameters::check(const double span, const double eps) const
{
  // A smoothed load (eps > 0) must lie wholly inside the wire; a point load may
  // stand on an anchor (x = 0 or L), where the wire is pinned.
  const bool point = eps == 0.;
  const auto inside = [&](const double x)
  { return point ? x >= 0. && x <= span : x > eps && x < span - eps; };
  const std::string range =
      point ? "[0, " + number_to_string(span) + "]"
            : "(" + number_to_string(eps) + ", " + number_to_string(span - eps) + ")";
  require(speed > 0., subsection + "/Speed", speed, "must be > 0");
  require(inside(initial_position), subsection + "/Initial position", initial_position,
          "the contact area must lie inside the section: allowed " + range + " m");
  require(final_position > initial_position && inside(final_position),
          subsection + "/Final position", final_position,
          "must be > Initial position = " + number_to_string(initial_position) +
              " m and inside the section " + range + " m");
  require(two_mass.head_mass > 0., subsection + "/Two-mass model/Head mass",
          two_mass.head_mass, "must be > 0");
  require(two_mass.frame_mass > 0., subsection + "/Two-mass model/Frame mass",
          two_mass.frame_mass, "must be > 0");
  for (unsigned int i = 0; i < 3; ++i)
    require(three_mass.masses[i] > 0., subsection + "/Three-mass model/Masses",
            three_mass.masses[i], "every mass must be > 0");
  mass_chain.check(subsection + "/Mass-chain model");
}
} // namespace pantocat
