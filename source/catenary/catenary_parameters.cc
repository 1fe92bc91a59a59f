#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>
#include <pantocat/catenary/catenary_parameters.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <algorithm>
#include <climits>
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

double CatenaryParameters::point_mass(const unsigned int j, const bool carrier_side) const
{
  return (carrier_side ? clamp_mass : contact_wire_clamp_mass) +
         half_dropper_mass(dropper_lengths[j]);
}

double CatenaryParameters::clamp_load(const unsigned int j, const bool carrier_side) const
{
  return point_mass(j, carrier_side) * gravity;
}

std::vector<double> CatenaryParameters::spans() const
{
  return span_lengths.empty() ? std::vector<double>(n_spans, span) : span_lengths;
}

double CatenaryParameters::length() const
{
  double total = 0.;
  for (const double l : spans())
    total += l;
  return total;
}

std::vector<double> CatenaryParameters::support_positions() const
{
  std::vector<double> x{0.};
  for (const double l : spans())
    x.push_back(x.back() + l);
  return x;
}

std::vector<double> CatenaryParameters::interior_supports() const
{
  std::vector<double> x = support_positions();
  return {x.begin() + 1, x.end() - 1};
}

std::vector<double> CatenaryParameters::steady_arm_positions() const
{
  if (steady_arm_supports.empty())
    return interior_supports();
  const std::vector<double> x = support_positions();
  std::vector<double> arms;
  for (const unsigned int k : steady_arm_supports)
    arms.push_back(x[k]);
  return arms;
}

std::vector<std::pair<double, double>> CatenaryParameters::presag_chords() const
{
  const std::vector<double> start = support_positions(), l = spans();
  std::vector<std::pair<double, double>> chords(l.size());
  for (unsigned int k = 0; k < l.size(); ++k)
    chords[k] = {start[k], l[k]};
  if (presag_reference == PresagReference::supports)
    return chords;
  std::vector<double> first(l.size(), 0.), last(l.size(), 0.);
  for (unsigned int j = n_droppers(); j-- > 0;) // droppers increase along the section
    first[dropper_spans[j]] = dropper_positions[j];
  for (unsigned int j = 0; j < n_droppers(); ++j)
    last[dropper_spans[j]] = dropper_positions[j];
  for (unsigned int k = 0; k < l.size(); ++k)
    chords[k] = {first[k], last[k] - first[k]};
  return chords;
}

std::vector<double> CatenaryParameters::dropper_target_heights() const
{
  if (!target_heights.empty())
    return target_heights;
  const std::vector<std::pair<double, double>> chords = presag_chords();
  std::vector<double> z(n_droppers());
  for (unsigned int j = 0; j < n_droppers(); ++j)
  {
    const auto [start, l] = chords[dropper_spans[j]];
    Assert(l > 0., dealii::ExcMessage("a pre-sag chord of length 0 (check_targets())"));
    const double xi = (dropper_positions[j] - start) / l;
    // Below the support chord (0 without support heights); + 0.: 0, not -0.
    z[j] = support_chord(dropper_positions[j]) - 4. * presag * xi * (1. - xi) + 0.;
  }
  return z;
}

std::vector<double> CatenaryParameters::dropper_target_displacements() const
{
  std::vector<double> z = dropper_target_heights();
  if (!support_heights.empty())
    for (unsigned int j = 0; j < z.size(); ++j)
      z[j] -= support_chord(dropper_positions[j]);
  return z;
}

double CatenaryParameters::support_chord(const double x,
                                         const unsigned int derivative) const
{
  const std::vector<double> s = support_positions();
  if (support_heights.size() != s.size()) // none, or a list check() refuses
    return 0.;
  if (x <= s.front() || x >= s.back())
    return derivative       ? 0.
           : x <= s.front() ? support_heights.front()
                            : support_heights.back();
  const unsigned int k = std::upper_bound(s.begin(), s.end(), x) - s.begin() - 1;
  const double slope = (support_heights[k + 1] - support_heights[k]) / (s[k + 1] - s[k]);
  return derivative ? slope : support_heights[k] + slope * (x - s[k]);
}

std::vector<double> CatenaryParameters::support_chord_kinks() const
{
  const std::vector<double> s = support_positions();
  std::vector<double> kinks(s.size(), 0.);
  if (support_heights.size() != s.size())
    return kinks;
  double left = 0.; // level before the first anchor
  for (unsigned int k = 0; k < s.size(); ++k)
  {
    const double right =
        k + 1 < s.size()
            ? (support_heights[k + 1] - support_heights[k]) / (s[k + 1] - s[k])
            : 0.;
    kinks[k] = right - left;
    left = right;
  }
  return kinks;
}

namespace
{

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
                         : "E I [N m^2], >= 0: used only with Scene/Messenger bending = "
                           "true (the paper's carrier is a string).");
  prm.declare_entry("Damping", number_to_string(defaults.damping), Double(0.),
                    "Viscous damping beta [N s/m^2], >= 0.");
}

/**
 * The lists of @p text separated by ';', every one kept: an empty list (also
 * after a last ';') is a span without droppers. (deal.II's split_string_list
 * drops a last empty element, so "a; b;" would be two lists.)
 */
std::vector<std::string> split_lists(const std::string& text)
{
  std::vector<std::string> lists{""};
  for (const char c : text)
    if (c == ';')
      lists.emplace_back();
    else
      lists.back() += c;
  return lists;
}

void parse_wire(dealii::ParameterHandler& prm, WireParameters& wire)
{
  wire.mass_per_length = prm.get_double("Mass per length");
  wire.tension = prm.get_double("Tension");
  wire.bending_stiffness = prm.get_double("Bending stiffness");
  wire.damping = prm.get_double("Damping");
}
} // namespace

void CatenaryParameters::move_old_names(dealii::ParameterHandler& prm,
                                        std::ostream& warnings)
{
  dealii::ParameterHandler defaults;
  declare_parameters(defaults);
  defaults.enter_subsection("Catenary");
  defaults.enter_subsection("Messenger");
  prm.enter_subsection("Catenary");
  bool moved = false;
  for (const char* entry : {"Mass per length", "Tension", "Bending stiffness", "Damping"})
  {
    const std::string given = [&]
    {
      prm.enter_subsection(old_messenger_subsection);
      const std::string value = prm.get(entry);
      prm.set(entry, defaults.get(entry));
      prm.leave_subsection();
      return value;
    }();
    if (given == defaults.get(entry))
      continue;
    prm.enter_subsection("Messenger");
    if (prm.get(entry) != defaults.get(entry))
      throw InputError(std::string("Catenary/Carrier/") + entry + " = " + given +
                       ": the messenger's entry is given under its old name and as "
                       "Catenary/Messenger/" +
                       entry + " = " + prm.get(entry) +
                       "; give it once, as Catenary/Messenger/" + entry);
    prm.set(entry, given);
    prm.leave_subsection();
    moved = true;
  }
  prm.leave_subsection();
  if (moved)
    warnings << "pantocat-fem: warning: subsection Catenary/Carrier is the old name of "
                "Catenary/Messenger (accepted; use the new name)\n";
}

void CatenaryParameters::place_droppers(const std::vector<std::vector<double>>& positions,
                                        const std::vector<double>& lengths)
{
  const std::vector<double> l = spans();
  const std::vector<double> supports = support_positions();
  const bool per_span = positions.size() > 1;
  if (per_span && positions.size() != l.size())
  {
    std::string empty; // which lists are empty, e.g. "list 4 empty"
    for (std::size_t k = 0; k < positions.size(); ++k)
      if (positions[k].empty())
        empty += (empty.empty() ? "" : ", ") + std::to_string(k + 1);
    require(false, "Catenary/Droppers/Positions",
            std::to_string(positions.size()) + " lists" +
                (empty.empty() ? "" : " (empty: list " + empty + ")"),
            "give one list for every span, or one per span (" + std::to_string(l.size()) +
                " spans) separated by ';'; every ';' starts a list, an empty one "
                "(also after a last ';') is a span without droppers");
  }
  dropper_positions.clear();
  dropper_spans.clear();
  std::vector<double> relative;
  for (unsigned int k = 0; k < l.size(); ++k)
  {
    const std::vector<double>& in_span = positions[per_span ? k : 0];
    for (unsigned int i = 0; i < in_span.size(); ++i)
    {
      const double x = in_span[i];
      if (!(x > 0. && x < l[k])) // the message only when it fails: O(n) in all
        require(false, "Catenary/Droppers/Positions", x,
                "positions are measured from the span's first support and must lie "
                "inside span " +
                    std::to_string(k + 1) + ", (0, " + number_to_string(l[k]) + ") m");
      if (i > 0 && !(x > in_span[i - 1]))
        require(false, "Catenary/Droppers/Positions", list_to_string(in_span),
                "positions in a span must be strictly increasing");
      dropper_positions.push_back(supports[k] + x);
      dropper_spans.push_back(k);
      relative.push_back(i);
    }
  }
  dropper_lengths.clear();
  const unsigned int n = dropper_positions.size();
  if (design == DropperDesign::designed)
  {
    dropper_lengths.assign(n, support_height); // a start for the design
    return;
  }
  const bool reused = !per_span && lengths.size() == positions[0].size();
  require(
      lengths.size() == n || reused, "Catenary/Droppers/Lengths", list_to_string(lengths),
      "needs one length per dropper of a span (" + std::to_string(positions[0].size()) +
          ") or of the section (" + std::to_string(n) + "), or Design = designed");
  for (unsigned int j = 0; j < n; ++j)
    dropper_lengths.push_back(reused ? lengths[static_cast<unsigned int>(relative[j])]
                                     : lengths[j]);
}

void CatenaryParameters::place_target_heights(const std::vector<double>& given,
                                              const bool one_list)
{
  const unsigned int n = n_droppers();
  const unsigned int in_span =
      std::count(dropper_spans.begin(), dropper_spans.end(), 0u); // span 1's droppers
  const bool reused = one_list && given.size() == in_span && n > 0;
  if (!given.empty() && !reused && given.size() != n)
    require(false, "Catenary/Droppers/Target heights", list_to_string(given),
            std::to_string(given.size()) + " heights given; allowed: one per dropper " +
                (one_list ? "of a span (" + std::to_string(in_span) + ") or " : "") +
                "of the section (" + std::to_string(n) +
                "), or none (the pre-sag's targets)");
  target_heights.clear();
  for (unsigned int j = 0; j < n && !given.empty(); ++j)
    target_heights.push_back(reused ? given[j % in_span] : given[j]);
}

void CatenaryParameters::declare_parameters(dealii::ParameterHandler& prm)
{
  const CatenaryParameters d;
  prm.enter_subsection("Catenary");
  prm.declare_entry("Span", "20", Double(0.),
                    "Length L of each span [m] (Sec. 2.2: one span of 20 m).");
  prm.declare_entry("Number of spans", "1", dealii::Patterns::Integer(1, 100000),
                    "Spans of the tension section, each Span long; both wires are "
                    "pinned at the section's ends x = 0 and x = n L.");
  prm.declare_entry("Span lengths", "", List(Double(0.), 0),
                    "Span lengths [m] first to last; replaces Span and Number of spans "
                    "when given.");
  prm.declare_entry("Encumbrance", "1", Double(),
                    "Encumbrance (system height) l_c: height of the messenger above the "
                    "contact wire at every support [m], boundary condition (3).");
  prm.declare_alias("Encumbrance", "Support height", true);
  prm.declare_entry("Gravity", "9.81", Double(0.),
                    "Gravitational acceleration g [m/s^2].");
  for (const char* messenger : {"Messenger", old_messenger_subsection})
  {
    prm.enter_subsection(messenger);
    declare_wire(prm, d.carrier, false);
    prm.leave_subsection();
  }
  prm.enter_subsection("Contact wire");
  declare_wire(prm, d.contact_wire, true);
  prm.leave_subsection();
  prm.enter_subsection("Droppers");
  prm.declare_entry("Positions", list_to_string(d.dropper_positions),
                    List(List(Double(), 0, UINT_MAX, ","), 1, UINT_MAX, ";"),
                    "Dropper positions [m] from each span's first support, increasing, "
                    "inside the span: one list for every span, or one list per span "
                    "separated by ';' (every ';' starts a list: an empty one, also "
                    "after a last ';', is a span without droppers).");
  prm.declare_entry("Lengths", list_to_string(d.dropper_lengths), List(Double(0.), 0),
                    "Dropper lengths l_j [m]: one per dropper of a span (reused in every "
                    "span) or one per dropper of the section; not read with Design = "
                    "designed.");
  prm.declare_entry("Design", "given", dealii::Patterns::Selection("given|designed"),
                    "given: the Lengths; designed: lengths from the static design "
                    "(form-finding) so that the static contact wire lies on its target "
                    "at every dropper, from the Pre-sag or the Target heights "
                    "(doc/catenaries.md).");
  prm.declare_entry("Pre-sag", "0", Double(0.),
                    "Pre-sag s [m] of the contact wire for Design = designed: targets "
                    "z = -4 s xi (1 - xi) at the dropper points, xi from 0 to 1 across "
                    "the Pre-sag reference (s below it midway).");
  prm.declare_entry("Pre-sag reference", "supports",
                    dealii::Patterns::Selection("supports|first and last dropper"),
                    "Where the pre-sag parabola of a span is zero: supports, xi = x/l "
                    "(x from the span's first support, l its length); first and last "
                    "dropper, xi = (x - x_first)/(x_last - x_first) (two droppers or "
                    "more in every span that has droppers).");
  prm.declare_entry("Unreachable targets", "refuse",
                    dealii::Patterns::Selection("refuse|release"),
                    "A target that a dropper could hold only by pushing (Design = "
                    "designed): refuse names it; release leaves that dropper at zero "
                    "force in the static state, the contact wire where its neighbours "
                    "put it (above the target), with a warning.");
  prm.declare_entry("Target heights", "", List(Double(), 0),
                    "Target heights [m] of the static contact wire at the droppers for "
                    "Design = designed (0 at the steady arms, negative below): one per "
                    "dropper of a span (reused in every span) or one per dropper of the "
                    "section; they replace the pre-sag (then Pre-sag = 0). Empty: from "
                    "the pre-sag.");
  prm.declare_entry("Mass per length", "0.14", Double(0.), "rho_d A_d [kg/m].");
  prm.declare_entry("Clamp mass", "0.25", List(Double(0.), 1, 2),
                    "Mass m_s of a clamp [kg], Eq. (4): one value for both wires, or "
                    "carrier, contact wire.");
  prm.declare_entry("Stiffness", "1e5", Double(0.),
                    "Axial stiffness k_d = EA/l [N/m] of an elastic dropper in tension "
                    "(Scene/Droppers = elastic); no force when slack.");
  prm.leave_subsection();
  prm.declare_entry("Point mass inertia", "false", dealii::Patterns::Bool(),
                    "false: clamp and dropper masses are loads only (Eq. (4), the "
                    "paper); true: they (and steady-arm masses) are in the mass matrix "
                    "too.");
  prm.enter_subsection("Supports");
  prm.declare_entry("Messenger support", "fixed",
                    dealii::Patterns::Selection("fixed|spring"),
                    "The messenger (the paper's carrier) at the supports between spans: "
                    "fixed at height l_c, or on a vertical spring preloaded to hold it "
                    "there statically.");
  prm.declare_alias("Messenger support", "Carrier support", true);
  prm.declare_entry("Messenger support stiffness", "5e5", Double(0.),
                    "[N/m], Messenger support = spring.");
  prm.declare_alias("Messenger support stiffness", "Carrier support stiffness", true);
  prm.declare_entry("Steady arm stiffness", "0", Double(0.),
                    "Vertical stiffness [N/m] of the steady arm holding the contact wire "
                    "at each support between spans, preloaded so that the static contact "
                    "wire is at 0 there; 0: no steady arms.");
  prm.declare_entry("Steady arm supports", "", List(dealii::Patterns::Integer(0), 0),
                    "Support numbers k (0 = the section's start, n = its end) that hold "
                    "the contact wire by a steady arm, increasing, each in 1..n-1 (the "
                    "section ends are anchors); empty: every support between spans.");
  prm.declare_entry("Steady arm mass", "0", Double(0.),
                    "Mass [kg] of a steady arm, lumped on the contact wire.");
  prm.declare_entry("Contact wire heights", "", List(Double(), 0),
                    "Heights [m] of the contact wire at every support, the section's "
                    "start to its end (n + 1 values; z = 0 the working height), the "
                    "messenger Encumbrance above each; between supports both wires run "
                    "on the straight chord, from which the pre-sag is measured. Empty: "
                    "0 at every support. On a line, the overlaps set their supports' "
                    "heights (Line/Overlap heights).");
  prm.leave_subsection();
  prm.enter_subsection("Stitch wire");
  StitchWireEntries::declare_parameters(prm);
  prm.leave_subsection();
  prm.declare_entry("Damping model", "viscous",
                    dealii::Patterns::Selection("viscous|rayleigh"),
                    "viscous: beta w_t of each wire (Damping in its subsection, Eq. "
                    "(2)); rayleigh: C = alpha M + beta K of the catenary, K without the "
                    "droppers (the form railway codes use).");
  prm.declare_entry("Rayleigh alpha", "0", Double(0.),
                    "alpha [1/s] of C = alpha M + beta K.");
  prm.declare_entry("Rayleigh beta", "0", Double(0.),
                    "beta [s] of C = alpha M + beta K.");
  prm.leave_subsection();
}

void CatenaryParameters::parse_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Catenary");
  span = prm.get_double("Span");
  n_spans = prm.get_integer("Number of spans");
  span_lengths = dealii::Utilities::string_to_double(
      dealii::Utilities::split_string_list(prm.get("Span lengths")));
  support_height = prm.get_double("Encumbrance");
  gravity = prm.get_double("Gravity");
  prm.enter_subsection("Messenger");
  parse_wire(prm, carrier);
  prm.leave_subsection();
  prm.enter_subsection("Contact wire");
  parse_wire(prm, contact_wire);
  prm.leave_subsection();
  prm.enter_subsection("Droppers");
  std::vector<std::vector<double>> positions;
  for (const std::string& group : split_lists(prm.get("Positions")))
    positions.push_back(
        dealii::Utilities::string_to_double(dealii::Utilities::split_string_list(group)));
  const std::vector<double> lengths = dealii::Utilities::string_to_double(
      dealii::Utilities::split_string_list(prm.get("Lengths")));
  design =
      prm.get("Design") == "designed" ? DropperDesign::designed : DropperDesign::given;
  presag = prm.get_double("Pre-sag");
  release_unreachable_targets = prm.get("Unreachable targets") == "release";
  presag_reference = prm.get("Pre-sag reference") == "supports"
                         ? PresagReference::supports
                         : PresagReference::first_and_last_dropper;
  const std::vector<double> targets = dealii::Utilities::string_to_double(
      dealii::Utilities::split_string_list(prm.get("Target heights")));
  dropper_mass_per_length = prm.get_double("Mass per length");
  const std::vector<double> clamps = dealii::Utilities::string_to_double(
      dealii::Utilities::split_string_list(prm.get("Clamp mass")));
  clamp_mass = clamps.front();
  contact_wire_clamp_mass = clamps.back();
  dropper_stiffness = prm.get_double("Stiffness");
  prm.leave_subsection();
  point_mass_inertia = prm.get_bool("Point mass inertia");
  prm.enter_subsection("Supports");
  carrier_support = prm.get("Messenger support") == "spring" ? CarrierSupport::spring
                                                             : CarrierSupport::fixed;
  carrier_support_stiffness = prm.get_double("Messenger support stiffness");
  steady_arm_stiffness = prm.get_double("Steady arm stiffness");
  steady_arm_mass = prm.get_double("Steady arm mass");
  steady_arm_supports.clear();
  for (const int k : dealii::Utilities::string_to_int(
           dealii::Utilities::split_string_list(prm.get("Steady arm supports"))))
    steady_arm_supports.push_back(k);
  support_heights = dealii::Utilities::string_to_double(
      dealii::Utilities::split_string_list(prm.get("Contact wire heights")));
  prm.leave_subsection();
  prm.enter_subsection("Stitch wire");
  StitchWireEntries stitch;
  stitch.parse_parameters(prm);
  prm.leave_subsection();
  damping = prm.get("Damping model") == "rayleigh" ? CatenaryDamping::rayleigh
                                                   : CatenaryDamping::viscous;
  rayleigh_alpha = prm.get_double("Rayleigh alpha");
  rayleigh_beta = prm.get_double("Rayleigh beta");
  prm.leave_subsection();
  place_droppers(positions, lengths);
  place_target_heights(targets, positions.size() == 1);
  place_stitch_wires(stitch);
  check();
}

void CatenaryParameters::check() const
{
  require(span > 0., "Catenary/Span", span, "must be > 0");
  // Before the lengths: Design = designed starts every length at l_c.
  require(support_height > 0., "Catenary/Encumbrance", support_height,
          "the encumbrance l_c (carrier above the contact wire at the supports) must "
          "be > 0");
  for (const double l : span_lengths)
    require(l > 0., "Catenary/Span lengths", l, "must be > 0");
  require(carrier.mass_per_length > 0., "Catenary/Messenger/Mass per length",
          carrier.mass_per_length, "must be > 0");
  require(carrier.tension > 0., "Catenary/Messenger/Tension", carrier.tension,
          "must be > 0");
  require(contact_wire.mass_per_length > 0., "Catenary/Contact wire/Mass per length",
          contact_wire.mass_per_length, "must be > 0");
  require(contact_wire.tension > 0. || contact_wire.bending_stiffness > 0.,
          "Catenary/Contact wire/Tension", contact_wire.tension,
          "tension and bending stiffness must not both be 0");
  require(dropper_spans.size() == dropper_positions.size(), "Catenary/Droppers/Positions",
          list_to_string(dropper_positions), "every dropper needs its span");
  require(dropper_lengths.size() == dropper_positions.size(), "Catenary/Droppers/Lengths",
          list_to_string(dropper_lengths),
          "needs one length per dropper position (" +
              std::to_string(dropper_positions.size()) + " positions given)");
  const double L = length();
  for (unsigned int j = 0; j < dropper_positions.size(); ++j)
  {
    // Each message is formed only when its check fails: O(n) in all.
    const double x = dropper_positions[j];
    if (!(x > 0. && x < L))
      require(false, "Catenary/Droppers/Positions", x,
              "dropper positions must lie inside the section (0, " + number_to_string(L) +
                  ") m");
    if (j > 0 && !(x > dropper_positions[j - 1]))
      require(false, "Catenary/Droppers/Positions", list_to_string(dropper_positions),
              "positions must be strictly increasing");
    if (!(dropper_lengths[j] > 0.))
      require(false, "Catenary/Droppers/Lengths", dropper_lengths[j], "must be > 0");
  }
  require(dropper_stitch_wire.empty() || dropper_stitch_wire.size() == n_droppers(),
          "Catenary/Stitch wire/Dropper positions", dropper_stitch_wire.size(),
          "every dropper needs the wire it hangs from");
  require(support_heights.empty() || support_heights.size() == number_of_spans() + 1,
          "Catenary/Supports/Contact wire heights", list_to_string(support_heights),
          "one height per support of the section (" +
              std::to_string(number_of_spans() + 1) + "), or none (0 at every support)");
  check_supports();
  check_targets();
  check_stitch_wires();
}

void CatenaryParameters::check_targets() const
{
  const std::string parameter = "Catenary/Droppers/Target heights";
  require(target_heights.empty() || target_heights.size() == n_droppers(), parameter,
          list_to_string(target_heights),
          "allowed: one per dropper of the section (" + std::to_string(n_droppers()) +
              "), or none (the pre-sag's targets)");
  require(target_heights.empty() || presag == 0., "Catenary/Droppers/Pre-sag", presag,
          "not together with " + parameter + " (" +
              std::to_string(target_heights.size()) +
              " heights given): the heights replace the pre-sag; allowed: Pre-sag = 0 "
              "with Target heights, or no Target heights");
  if (design != DropperDesign::designed || !target_heights.empty() ||
      presag_reference != PresagReference::first_and_last_dropper)
    return;
  std::vector<unsigned int> in_span(number_of_spans(), 0);
  for (const unsigned int k : dropper_spans)
    ++in_span[k];
  for (unsigned int k = 0; k < in_span.size(); ++k)
    require(in_span[k] != 1, "Catenary/Droppers/Pre-sag reference",
            "first and last dropper",
            "span " + std::to_string(k + 1) +
                " has 1 dropper, and the parabola is zero at two; allowed: supports, or "
                "at least 2 droppers in every span that has droppers");
}

void CatenaryParameters::check_supports() const
{
  require(carrier_support != CarrierSupport::spring || carrier_support_stiffness > 0.,
          "Catenary/Supports/Messenger support stiffness", carrier_support_stiffness,
          "must be > 0 with Messenger support = spring (a spring of stiffness 0 holds "
          "nothing; Messenger support = fixed holds the messenger rigidly)");
  require(steady_arm_supports.empty() || steady_arm_stiffness > 0.,
          "Catenary/Supports/Steady arm supports", list_to_string(steady_arm_supports),
          "names supports for steady arms, but Steady arm stiffness = 0 means no steady "
          "arms; allowed: a Steady arm stiffness > 0, or an empty list");
  const unsigned int n = number_of_spans();
  const std::string parameter = "Catenary/Supports/Steady arm supports";
  for (unsigned int i = 0; i < steady_arm_supports.size(); ++i)
  {
    const unsigned int k = steady_arm_supports[i];
    if (!(k >= 1 && k + 1 <= n))
      require(false, parameter, k,
              (k == 0 || k == n
                   ? "support " + std::to_string(k) +
                         " is a section anchor (both wires pinned there)"
                   : "support " + std::to_string(k) + " does not exist in a section of " +
                         std::to_string(n) + " spans") +
                  "; allowed: supports between spans, 1.." + std::to_string(n - 1));
    if (i > 0 && k <= steady_arm_supports[i - 1])
      require(false, parameter, k, "support numbers must be strictly increasing");
  }
}
} // namespace pantocat
