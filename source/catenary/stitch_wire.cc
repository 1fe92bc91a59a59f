#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>
#include <pantocat/catenary/catenary_parameters.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>

namespace pantocat
{
using dealii::Patterns::Double;
using dealii::Patterns::List;

namespace
{
const std::string section = "Catenary/Stitch wire/";

std::vector<double> doubles(const std::string& text)
{
  return dealii::Utilities::string_to_double(dealii::Utilities::split_string_list(text));
}

/// Value @p i of an entry given once for all stitched supports or once per support.
double per_support(const std::vector<double>& values, const unsigned int i)
{
  return values[values.size() == 1 ? 0 : i];
}

/// Refuses an entry that is neither one value nor one per stitched support.
template <typename Value>
void require_per_support(const std::vector<Value>& values, const unsigned int n,
                         const std::string& entry, const std::string& text)
{
  require(values.size() == 1 || values.size() == n, section + entry, text,
          "give one value for every stitched support, or one per support of Supports (" +
              std::to_string(n) + " supports)");
}

/// Refuses support numbers outside 1..n-1 (the section's anchors are 0 and n).
void check_support_numbers(const std::vector<unsigned int>& supports,
                           const unsigned int n)
{
  for (unsigned int i = 0; i < supports.size(); ++i)
  {
    const unsigned int k = supports[i];
    if (!(k >= 1 && k + 1 <= n))
      require(false, section + "Supports", k,
              (k == 0 || k == n
                   ? "support " + std::to_string(k) +
                         " is a section anchor, where a stitch wire would be clamped "
                         "outside the section"
                   : "support " + std::to_string(k) + " does not exist in a section of " +
                         std::to_string(n) + " spans") +
                  "; allowed: supports between spans, 1.." + std::to_string(n - 1));
    if (i > 0 && k <= supports[i - 1])
      require(false, section + "Supports", list_to_string(supports),
              "support numbers must be strictly increasing");
  }
}
} // namespace

void StitchWireEntries::declare_parameters(dealii::ParameterHandler& prm)
{
  const StitchWireEntries d;
  prm.declare_entry(
      "Length", list_to_string(d.lengths), List(Double(0.), 1),
      "Length [m] of the stitch wire, centred on its support and clamped to "
      "the carrier at both ends; one value for every stitched support or "
      "one per support of Supports; 0: no stitch wire (the default: a "
      "simple catenary).");
  prm.declare_entry("Supports", "", List(dealii::Patterns::Integer(0), 0),
                    "Support numbers k (0 = the section's start, n = its end) with a "
                    "stitch wire, increasing, each in 1..n-1; empty: every support "
                    "between spans.");
  prm.declare_entry(
      "Tension", list_to_string(d.tensions), List(Double(0.), 1),
      "Tension T [N] of the stitch wire, > 0; one value or one per support.");
  prm.declare_entry(
      "Mass per length", list_to_string(d.masses_per_length), List(Double(0.), 1),
      "rho A [kg/m] of the stitch wire, > 0; one value or one per support.");
  prm.declare_entry("Damping", list_to_string(d.dampings), List(Double(0.), 1),
                    "Viscous damping beta [N s/m^2] of the stitch wire (Damping model = "
                    "viscous; with rayleigh it takes C = alpha M + beta K like the "
                    "wires); one value or one per support.");
  prm.declare_entry(
      "Clamp mass", list_to_string(d.clamp_masses), List(Double(0.), 1),
      "Mass [kg] of each of the two clamps that hold the stitch wire on the "
      "carrier; one value or one per support.");
  prm.declare_entry("Dropper positions", "",
                    List(List(Double(), 0, UINT_MAX, ","), 0, UINT_MAX, ";"),
                    "Positions [m] of the droppers that hang from the stitch wire, "
                    "measured from its support (negative: in the span before it), each "
                    "a dropper of the section strictly inside the stitch wire; one list "
                    "for every stitched support or one per support separated by ';'; "
                    "empty: every dropper strictly inside its length.");
}

void StitchWireEntries::parse_parameters(dealii::ParameterHandler& prm)
{
  lengths = doubles(prm.get("Length"));
  supports.clear();
  for (const int k : dealii::Utilities::string_to_int(
           dealii::Utilities::split_string_list(prm.get("Supports"))))
    supports.push_back(k);
  tensions = doubles(prm.get("Tension"));
  masses_per_length = doubles(prm.get("Mass per length"));
  dampings = doubles(prm.get("Damping"));
  clamp_masses = doubles(prm.get("Clamp mass"));
  dropper_positions.clear();
  std::vector<std::string> lists{""};
  for (const char c : prm.get("Dropper positions")) // every ';' starts a list
    if (c == ';')
      lists.emplace_back();
    else
      lists.back() += c;
  for (const std::string& list : lists)
    dropper_positions.push_back(doubles(list));
}

namespace
{
/**
 * The droppers of @p c that hang from @p wire: those at @p given positions
 * from its support (each a dropper of the section strictly inside it), or,
 * with none given, every dropper strictly inside it.
 */
std::vector<unsigned int> hanging_droppers(const CatenaryParameters& c,
                                           const StitchWire& wire,
                                           const std::vector<double>& given)
{
  const std::vector<double>& x = c.dropper_positions;
  std::vector<unsigned int> droppers;
  if (given.empty())
  {
    for (auto it = std::upper_bound(x.begin(), x.end(), wire.start());
         it != x.end() && *it < wire.end(); ++it)
      droppers.push_back(it - x.begin());
    return droppers;
  }
  const std::string where = "the stitch wire at support " + std::to_string(wire.support) +
                            " (x = " + number_to_string(wire.centre) + " m)";
  for (const double p : given)
  {
    const double at = wire.centre + p;
    require(at > wire.start() && at < wire.end(), section + "Dropper positions", p,
            "outside " + where + ", which reaches from " +
                number_to_string(-0.5 * wire.length) + " to " +
                number_to_string(0.5 * wire.length) +
                " m of its support; allowed: positions strictly inside it");
    const auto it = std::lower_bound(x.begin(), x.end(), at - 1e-6);
    require(it != x.end() && std::abs(*it - at) <= 1e-6, section + "Dropper positions", p,
            "the section has no dropper at x = " + number_to_string(at) + " m (" + where +
                "); allowed: positions of droppers of Catenary/Droppers/Positions");
    droppers.push_back(it - x.begin());
  }
  std::sort(droppers.begin(), droppers.end());
  require(std::adjacent_find(droppers.begin(), droppers.end()) == droppers.end(),
          section + "Dropper positions", list_to_string(given),
          "a dropper of " + where + " is listed twice");
  return droppers;
}
} // namespace

void CatenaryParameters::place_stitch_wires(const StitchWireEntries& given)
{
  const unsigned int n = number_of_spans();
  std::vector<unsigned int> supports = given.supports;
  check_support_numbers(supports, n);
  if (supports.empty())
    for (unsigned int k = 1; k < n; ++k)
      supports.push_back(k);
  const unsigned int m = supports.size();
  require_per_support(given.lengths, m, "Length", list_to_string(given.lengths));
  require_per_support(given.tensions, m, "Tension", list_to_string(given.tensions));
  require_per_support(given.masses_per_length, m, "Mass per length",
                      list_to_string(given.masses_per_length));
  require_per_support(given.dampings, m, "Damping", list_to_string(given.dampings));
  require_per_support(given.clamp_masses, m, "Clamp mass",
                      list_to_string(given.clamp_masses));
  require_per_support(given.dropper_positions, m, "Dropper positions",
                      std::to_string(given.dropper_positions.size()) + " lists");
  const std::vector<double> x = support_positions();
  stitch_wires.clear();
  for (unsigned int i = 0; i < m; ++i)
  {
    StitchWire s;
    s.support = supports[i];
    s.centre = x[s.support];
    s.length = per_support(given.lengths, i);
    if (s.length == 0.)
      continue; // no stitch wire at this support
    s.tension = per_support(given.tensions, i);
    s.mass_per_length = per_support(given.masses_per_length, i);
    s.damping = per_support(given.dampings, i);
    s.clamp_mass = per_support(given.clamp_masses, i);
    stitch_wires.push_back(s);
  }
  check_stitch_wires(); // inside the section and its spans, before the droppers
  dropper_stitch_wire.assign(n_droppers(), no_stitch_wire);
  for (unsigned int i = 0, w = 0; i < m; ++i)
    if (w < stitch_wires.size() && stitch_wires[w].support == supports[i])
    {
      const std::vector<double>& positions =
          given.dropper_positions[given.dropper_positions.size() == 1 ? 0 : i];
      stitch_wires[w].droppers = hanging_droppers(*this, stitch_wires[w], positions);
      for (const unsigned int j : stitch_wires[w].droppers)
        dropper_stitch_wire[j] = w;
      ++w;
    }
}

void CatenaryParameters::check_stitch_wires() const
{
  const std::vector<double> x = support_positions(), l = spans();
  const double L = length();
  for (unsigned int w = 0; w < stitch_wires.size(); ++w)
  {
    const StitchWire& s = stitch_wires[w];
    const std::string at = "the stitch wire at support " + std::to_string(s.support) +
                           " (x = " + number_to_string(s.centre) + " m)";
    require(s.support >= 1 && s.support < l.size() && s.centre == x[s.support],
            section + "Supports", s.support,
            "a stitch wire is centred on a support between spans, 1.." +
                std::to_string(l.size() - 1));
    const double reach = std::min(l[s.support - 1], l[s.support]);
    require(s.start() >= 0. && s.end() <= L, section + "Length", s.length,
            at + " would be clamped at x = " +
                number_to_string(s.start() < 0. ? s.start() : s.end()) +
                " m, outside the section [0, " + number_to_string(L) +
                "] m; allowed: 0 <= length < " + number_to_string(2. * reach) +
                " m (twice the shorter of its two spans)");
    require(s.length > 0. && s.length < 2. * reach, section + "Length", s.length,
            at + " is longer than its spans allow (" +
                number_to_string(l[s.support - 1]) + " and " +
                number_to_string(l[s.support]) +
                " m: its clamps must lie inside them); allowed: 0 <= length < " +
                number_to_string(2. * reach) + " m");
    if (w > 0 && !(stitch_wires[w - 1].end() < s.start()))
      require(false, section + "Length", s.length,
              at + " overlaps the stitch wire at support " +
                  std::to_string(stitch_wires[w - 1].support) +
                  "; allowed: lengths whose halves add up to less than the span between "
                  "two stitched supports");
    require(s.tension > 0., section + "Tension", s.tension,
            "must be > 0 for " + at + " (a string without tension carries nothing)");
    require(s.mass_per_length > 0., section + "Mass per length", s.mass_per_length,
            "must be > 0 for " + at + " (its mass matrix)");
    for (const unsigned int j : s.droppers)
      require(j < n_droppers() && dropper_positions[j] > s.start() &&
                  dropper_positions[j] < s.end(),
              section + "Dropper positions",
              j < n_droppers() ? dropper_positions[j] - s.centre : -1.,
              "outside " + at + "; allowed: droppers strictly inside it");
  }
}
} // namespace pantocat
