#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>
#include <pantocat/pantograph/pantograph_registry.h>
#include <pantocat/scene/scene_parameters.h>

namespace pantocat
{
using dealii::Patterns::Bool;
using dealii::Patterns::Selection;

namespace
{
const char* contact_laws = "unilateral|bilateral|penalty";

Constraint::Kind contact_kind(const std::string& name)
{
  return name == "bilateral" ? Constraint::Kind::bilateral : Constraint::Kind::unilateral;
}

/// Declares Contact stiffness and Contact damping (defaults of @p first).
void declare_contact_law(dealii::ParameterHandler& prm, const PantographCase& first)
{
  const bool penalty = first.contact_compliance.stiffness > 0.;
  prm.declare_entry("Contact stiffness",
                    number_to_string(penalty ? first.contact_compliance.stiffness : 5e4),
                    dealii::Patterns::Double(),
                    "k_c [N/m] of Contact = penalty: lambda_p = k_c x penetration "
                    "(+ damping), 0 when separated; > 0. 50 kN/m is typical.");
  prm.declare_entry("Contact damping", number_to_string(first.contact_compliance.damping),
                    dealii::Patterns::Double(),
                    "c_c [N s/m] of Contact = penalty: lambda_p = max(0, -k_c g - c_c "
                    "dg/dt) in contact; >= 0.");
}

/// The contact law of the current subsection's Contact entries.
void parse_contact_law(dealii::ParameterHandler& prm, PantographCase& p)
{
  const std::string law = prm.get("Contact");
  p.contact = contact_kind(law);
  p.contact_compliance = {};
  if (law != "penalty")
    return;
  p.contact_compliance = {prm.get_double("Contact stiffness"),
                          prm.get_double("Contact damping")};
  require(p.contact_compliance.stiffness > 0., p.contact_entry("Contact stiffness"),
          p.contact_compliance.stiffness, "must be > 0 with Contact = penalty");
  require(p.contact_compliance.damping >= 0., p.contact_entry("Contact damping"),
          p.contact_compliance.damping, "must be >= 0");
}

std::string pantograph_selection()
{
  return pantograph_model_selection() + "|moving force|absent";
}

std::string pantograph_subsection(const unsigned int k)
{
  return k == 1 ? "Pantograph" : "Pantograph " + std::to_string(k);
}
} // namespace

bool PantographCase::has_body() const
{
  return find_pantograph_model(model) != nullptr;
}

std::string PantographCase::model_parameter() const
{
  return parameters.subsection == "Pantograph" ? "Scene/Pantograph"
                                               : parameters.subsection + "/Model";
}

std::string PantographCase::contact_entry(const std::string& entry) const
{
  return (parameters.subsection == "Pantograph" ? "Scene/"
                                                : parameters.subsection + "/") +
         entry;
}

std::string PantographCase::contact_law() const
{
  if (contact_compliance.stiffness > 0.)
    return "penalty";
  return contact == Constraint::Kind::bilateral ? "bilateral" : "unilateral";
}

bool SceneParameters::has_pantograph_body() const
{
  for (const PantographCase& p : pantographs)
    if (p.has_body())
      return true;
  return false;
}

bool SceneParameters::has_moving_force() const
{
  for (const PantographCase& p : pantographs)
    if (p.is_moving_force())
      return true;
  return false;
}

void SceneParameters::declare_parameters(dealii::ParameterHandler& prm,
                                         const unsigned int n_pantographs,
                                         const PantographCase& first)
{
  prm.enter_subsection("Scene");
  prm.declare_entry("Messenger", "elastic", Selection("elastic|rigid"),
                    "elastic: the messenger (the paper's carrier) is a string, Eq. (2); "
                    "rigid: it stays at the support height l_c (no unknowns).");
  prm.declare_alias("Messenger", "Carrier", true);
  prm.declare_entry("Contact wire", "elastic", Selection("elastic|rigid"),
                    "elastic: the contact wire is an Euler-Bernoulli beam, Eq. (2); "
                    "rigid: it stays at height 0 (no unknowns; e.g. a pantograph "
                    "pressing on a rigid wire).");
  prm.declare_entry("Messenger tension", "true", Bool(),
                    "Tension T_c of the messenger (the paper's carrier).");
  prm.declare_alias("Messenger tension", "Carrier tension", true);
  prm.declare_entry("Contact wire tension", "true", Bool(),
                    "Tension T_w of the contact wire.");
  prm.declare_entry(
      "Messenger bending", "false", Bool(),
      "Bending stiffness E I_c (Catenary/Messenger/Bending stiffness) of the "
      "carrier: the paper's carrier is a string; with FEM this needs "
      "Discretisation/Messenger element = cubic Hermite.");
  prm.declare_alias("Messenger bending", "Carrier bending", true);
  prm.declare_entry("Contact wire bending", "true", Bool(),
                    "Bending stiffness E I of the contact wire.");
  prm.declare_entry("Gravity", "true", Bool(),
                    "Weight of the wires (and of clamps and droppers if those act).");
  prm.declare_entry("Damping", "true", Bool(),
                    "Viscous damping beta of the wires (the pantograph's dampers belong "
                    "to its model).");
  prm.declare_entry("Clamp and dropper masses", "true", Bool(),
                    "Weights of the suspension clamps and half droppers as point loads, "
                    "Eq. (4) (needs Gravity and droppers).");
  prm.declare_entry("Droppers", "unilateral",
                    Selection("unilateral|bilateral|elastic|absent"),
                    "unilateral: inextensible droppers that may slacken (Sec. 5.3, the "
                    "paper's model); bilateral: always taut, Eq. (4); elastic: "
                    "tension-only springs of stiffness Catenary/Droppers/Stiffness and "
                    "unstretched length l_j, no force when slack (a compliant unilateral "
                    "constraint); absent: no droppers.");
  prm.declare_entry("Number of pantographs", "1", dealii::Patterns::Integer(1, 16),
                    "Pantographs running on the catenary, 1 to 16 (a train raises a "
                    "few on one tension section; the moving contacts border the "
                    "constraint system densely, so a step costs O(n p + p^3) for p "
                    "pantographs): pantograph 1 is Pantograph, "
                    "Contact and Moving force here with subsection Pantograph; "
                    "pantograph k >= 2 is subsection Pantograph k (entries Model, "
                    "Contact, Moving force and those of subsection Pantograph), "
                    "whose entries not given take pantograph 1's values.");
  prm.declare_entry(
      "Pantograph spacing", "0", dealii::Patterns::Double(),
      "s [m], >= 0. 0: every Pantograph k gives its own Initial and Final position "
      "and Speed. s > 0: pantograph k >= 2 runs (k - 1) s behind pantograph 1 at "
      "its speed (Initial position x_p1(0) - (k - 1) s, Final position likewise; "
      "the entries of Pantograph k are then not read); every pantograph must stay "
      "inside the wires' domain for the whole run. The TSI spaces "
      "pantographs 200 m apart at >= 250 km/h; the paper's 20 m span holds none.");
  prm.declare_entry("Pantograph", "two-mass", Selection(pantograph_selection()),
                    "Model of pantograph 1. two-mass: the lumped-mass model (12); "
                    "three-mass: a chain of head, upper and lower frame (subsection "
                    "Pantograph/Three-mass model); mass-chain: n bodies in a chain "
                    "with static and aerodynamic uplift (subsection "
                    "Pantograph/Mass-chain model, doc/pantographs.md); moving force: "
                    "a prescribed constant force (Moving force) moving with v_p; "
                    "absent: no pantograph.");
  prm.declare_entry("Contact", "unilateral", Selection(contact_laws),
                    "Pantograph-wire contact (32): unilateral (a rigid contact that may "
                    "be lost), bilateral (always in contact, a smooth case) or penalty "
                    "(a compliant unilateral contact: force k_c x penetration, Contact "
                    "stiffness and Contact damping).");
  declare_contact_law(prm, PantographCase{});
  prm.declare_entry("Moving force", "100", dealii::Patterns::Double(),
                    "Magnitude [N] of the upward force for Pantograph = moving force, "
                    "distributed by the load shape of subsection Discretisation.");
  prm.declare_entry("Initial state", "static equilibrium",
                    Selection("static equilibrium|rest|sine mode"),
                    "static equilibrium: the catenary at rest under its loads and the "
                    "initial contact force (or the moving force at x_p(0)); rest: "
                    "undeformed and at rest; sine mode: contact wire w = A sin(k pi x/L) "
                    "at rest. rest and sine mode need a scene without constraints.");
  prm.declare_entry("Initial mode", "1", dealii::Patterns::Integer(1),
                    "k of the sine mode.");
  prm.declare_entry("Initial amplitude", "0.01", dealii::Patterns::Double(),
                    "A of the sine mode [m].");
  prm.leave_subsection();
  PantographParameters::declare_parameters(prm);
  for (unsigned int k = 2; k <= n_pantographs; ++k)
    declare_further_pantograph(prm, pantograph_subsection(k), first);
}

void SceneParameters::declare_further_pantograph(dealii::ParameterHandler& prm,
                                                 const std::string& subsection,
                                                 const PantographCase& first)
{
  PantographParameters::declare_parameters(prm, subsection, first.parameters);
  prm.enter_subsection(subsection);
  prm.declare_entry("Model", first.model, Selection(pantograph_selection()),
                    "As Scene/Pantograph, for this pantograph.");
  prm.declare_entry("Contact", first.contact_law(), Selection(contact_laws),
                    "As Scene/Contact, for this pantograph.");
  declare_contact_law(prm, first);
  prm.declare_entry("Moving force", number_to_string(first.moving_force),
                    dealii::Patterns::Double(),
                    "As Scene/Moving force, for this pantograph.");
  prm.leave_subsection();
}

unsigned int SceneParameters::number_of_pantographs(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Scene");
  const unsigned int n = prm.get_integer("Number of pantographs");
  prm.leave_subsection();
  return n;
}

std::string to_string(const DropperModel model)
{
  switch (model)
  {
  case DropperModel::unilateral:
    return "unilateral";
  case DropperModel::bilateral:
    return "bilateral";
  case DropperModel::elastic:
    return "elastic";
  case DropperModel::absent:
    break;
  }
  return "absent";
}

void SceneParameters::parse_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Scene");
  carrier = prm.get("Messenger") == "rigid" ? WireModel::rigid : WireModel::elastic;
  contact_wire =
      prm.get("Contact wire") == "rigid" ? WireModel::rigid : WireModel::elastic;
  carrier_tension = prm.get_bool("Messenger tension");
  contact_wire_tension = prm.get_bool("Contact wire tension");
  contact_wire_bending = prm.get_bool("Contact wire bending");
  carrier_bending = prm.get_bool("Messenger bending");
  gravity = prm.get_bool("Gravity");
  damping = prm.get_bool("Damping");
  clamp_and_dropper_masses = prm.get_bool("Clamp and dropper masses");
  const std::string d = prm.get("Droppers");
  droppers = d == "absent"      ? DropperModel::absent
             : d == "bilateral" ? DropperModel::bilateral
             : d == "elastic"   ? DropperModel::elastic
                                : DropperModel::unilateral;
  pantographs.assign(prm.get_integer("Number of pantographs"), PantographCase{});
  pantograph_spacing = prm.get_double("Pantograph spacing");
  pantographs[0].model = prm.get("Pantograph");
  parse_contact_law(prm, pantographs[0]);
  pantographs[0].moving_force = prm.get_double("Moving force");
  const std::string s = prm.get("Initial state");
  initial_shape = s == "rest"        ? InitialShape::rest
                  : s == "sine mode" ? InitialShape::sine_mode
                                     : InitialShape::static_equilibrium;
  initial_mode = prm.get_integer("Initial mode");
  initial_amplitude = prm.get_double("Initial amplitude");
  prm.leave_subsection();
  pantographs[0].parameters.parse_parameters(prm);
  for (unsigned int k = 2; k <= pantographs.size(); ++k)
  {
    PantographCase& p = pantographs[k - 1];
    const std::string subsection = pantograph_subsection(k);
    p.parameters.parse_parameters(prm, subsection);
    prm.enter_subsection(subsection);
    p.model = prm.get("Model");
    parse_contact_law(prm, p);
    p.moving_force = prm.get_double("Moving force");
    prm.leave_subsection();
    if (pantograph_spacing > 0.)
    {
      const PantographParameters& first = pantographs[0].parameters;
      const double behind = (k - 1) * pantograph_spacing;
      p.parameters.initial_position = first.initial_position - behind;
      p.parameters.final_position = first.final_position - behind;
      p.parameters.speed = first.speed;
      p.parameters.speed_ramp = first.speed_ramp; // the same motion, 200 m behind
    }
  }
}

void SceneParameters::check_spacing(const double length, const double margin) const
{
  require(pantograph_spacing >= 0., "Scene/Pantograph spacing", pantograph_spacing,
          "must be >= 0 (0: each pantograph gives its own positions)");
  if (pantograph_spacing == 0. || pantographs.size() < 2)
    return;
  // Every pantograph moves forwards, pantograph k between x_p1(0) - (k - 1) s and
  // x_p1(t_e) - (k - 1) s: the last one starts furthest back, the first one ends
  // furthest ahead (PantographParameters::check).
  const PantographParameters& first = pantographs[0].parameters;
  const double n = pantographs.size();
  const double last = first.initial_position - (n - 1.) * pantograph_spacing;
  // A point load (margin 0) may start on the anchor x = 0; a smoothed one
  // must lie wholly inside.
  const double largest = (first.initial_position - margin) / (n - 1.);
  require(margin == 0. ? last >= 0. : last > margin, "Scene/Pantograph spacing",
          pantograph_spacing,
          "puts pantograph " + std::to_string(pantographs.size()) +
              " at x_p(0) = " + number_to_string(last) + " m, outside the section " +
              (margin == 0. ? "[0, " + number_to_string(length) + "]"
                            : "(" + number_to_string(margin) + ", " +
                                  number_to_string(length - margin) + ")") +
              " m; allowed: 0 <= s " + (margin == 0. ? "<= " : "< ") +
              number_to_string(largest) + " m with Pantograph/Initial position = " +
              number_to_string(first.initial_position) + " m");
}

void SceneParameters::check() const
{
  if (carrier == WireModel::elastic)
    require(carrier_tension || carrier_bending, "Scene/Messenger tension", "false",
            "with Messenger bending = false the elastic carrier has no stiffness; enable "
            "one of them or set Messenger = rigid");
  if (contact_wire == WireModel::elastic)
    require(contact_wire_tension || contact_wire_bending, "Scene/Contact wire tension",
            "false",
            "with Contact wire bending = false the elastic contact wire has no "
            "stiffness; enable one of them or set Contact wire = rigid");
  for (const PantographCase& p : pantographs)
    require(!(p.is_moving_force() && contact_wire == WireModel::rigid),
            p.model_parameter(), "moving force",
            "a prescribed force on a rigid contact wire does nothing; allowed with "
            "Contact wire = elastic");
  require(!(carrier == WireModel::rigid && contact_wire == WireModel::rigid &&
            droppers != DropperModel::absent),
          "Scene/Droppers", to_string(droppers),
          "droppers between a rigid carrier and a rigid contact wire connect nothing; "
          "allowed: absent");
  if (initial_shape != InitialShape::static_equilibrium)
    require(!has_droppers() && !has_pantograph_body(), "Scene/Initial state",
            initial_shape == InitialShape::rest ? "rest" : "sine mode",
            "a state that ignores the constraints needs a scene without them: allowed "
            "only with Droppers = absent and Pantograph = moving force or absent");
  if (initial_shape == InitialShape::sine_mode)
    require(contact_wire == WireModel::elastic, "Scene/Initial state", "sine mode",
            "needs Contact wire = elastic");
}
} // namespace pantocat
