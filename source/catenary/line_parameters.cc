#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>
#include <pantocat/catenary/line_parameters.h>

#include <deal.II/base/utilities.h>

#include <algorithm>

namespace pantocat
{
namespace
{

/// Linear interpolation through the points (@p x, @p z), x increasing.
double interpolate(const std::vector<double>& x, const std::vector<double>& z,
                   const double at)
{
  if (at <= x.front())
    return z.front();
  if (at >= x.back())
    return z.back();
  const unsigned int k = std::upper_bound(x.begin(), x.end(), at) - x.begin() - 1;
  return z[k] + (z[k + 1] - z[k]) * (at - x[k]) / (x[k + 1] - x[k]);
}
} // namespace

double LineParameters::outgoing_height(const std::vector<double>& o,
                                       const double xi) const
{
  // The points (O_i, H_i) and (middle, 0) unless the middle is a support.
  const double middle = 0.5 * (o.front() + o.back());
  std::vector<double> x, z;
  for (unsigned int i = 0; i < o.size(); ++i)
  {
    if (i > 0 && o[i - 1] < middle && middle < o[i])
      x.push_back(middle), z.push_back(0.);
    x.push_back(o[i]), z.push_back(overlap_heights[i]);
  }
  return interpolate(x, z, xi);
}

std::vector<CatenaryParameters>
LineParameters::sections(const CatenaryParameters& section) const
{
  if (!is_line())
    return {section};
  const std::vector<double> supports = section.support_positions();
  const unsigned int n = section.number_of_spans(), o = overlap_spans;
  // The overlap's supports from its first: the section's last o + 1.
  std::vector<double> overlap(supports.end() - o - 1, supports.end());
  for (double& x : overlap)
    x -= supports[n - o];
  const double D = overlap.back();
  std::vector<CatenaryParameters> line;
  for (unsigned int k = 0; k < n_sections; ++k)
  {
    CatenaryParameters c = section;
    c.name = "section " + std::to_string(k + 1);
    c.start = k * supports[n - o];
    if (c.support_heights.empty())
      c.support_heights.assign(n + 1, 0.);
    const bool incoming = k > 0, outgoing = k + 1 < n_sections;
    for (unsigned int i = 0; i <= o; ++i)
    {
      if (incoming)
        c.support_heights[i] = overlap_heights[o - i];
      if (outgoing)
        c.support_heights[n - o + i] = overlap_heights[i];
    }
    // The section's own targets on its chord, then the overlaps' in their spans.
    c.target_heights = c.dropper_target_heights();
    c.presag = 0.;
    for (unsigned int j = 0; j < c.n_droppers(); ++j)
    {
      const double x = c.dropper_positions[j];
      if (incoming && x < D)
        c.target_heights[j] = outgoing_height(overlap, D - x);
      if (outgoing && x > supports[n - o])
        c.target_heights[j] = outgoing_height(overlap, x - supports[n - o]);
    }
    line.push_back(std::move(c));
  }
  return line;
}

std::vector<std::pair<double, double>>
LineParameters::overlaps(const CatenaryParameters& section) const
{
  const std::vector<double> supports = section.support_positions();
  const double step = supports[supports.size() - 1 - overlap_spans];
  std::vector<std::pair<double, double>> list;
  for (unsigned int k = 1; k < n_sections; ++k)
    list.emplace_back(k * step, (k - 1) * step + supports.back());
  return list;
}

double LineParameters::length(const CatenaryParameters& section) const
{
  const std::vector<double> supports = section.support_positions();
  if (!is_line())
    return supports.back();
  return (n_sections - 1) * supports[supports.size() - 1 - overlap_spans] +
         supports.back();
}

void LineParameters::declare_parameters(dealii::ParameterHandler& prm)
{
  using namespace dealii::Patterns;
  prm.enter_subsection("Line");
  prm.declare_entry("Number of sections", "1", Integer(1),
                    "Tension sections along the line, each with the data of subsection "
                    "Catenary; consecutive ones are joined by an overlap. 1: the "
                    "section alone.");
  prm.declare_entry("Overlap spans", "3", Integer(0),
                    "Spans o that two consecutive sections share (supports O_0 .. O_o; "
                    "section k+1 starts at section k's support n - o); >= 1, at most "
                    "half the section's spans.");
  prm.declare_entry("Overlap heights", "0, 0, 0.2, 0.5", List(Double()),
                    "Heights H_0 .. H_o [m] of the outgoing contact wire at the "
                    "overlap's supports (z = 0 working height; H_o at its anchor): it "
                    "follows straight lines through them and through z = 0 at the "
                    "overlap's middle; the incoming wire mirrors it.");
  prm.leave_subsection();
}

void LineParameters::parse_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Line");
  n_sections = prm.get_integer("Number of sections");
  overlap_spans = prm.get_integer("Overlap spans");
  overlap_heights = dealii::Utilities::string_to_double(
      dealii::Utilities::split_string_list(prm.get("Overlap heights")));
  prm.leave_subsection();
}

void LineParameters::check(const CatenaryParameters& section) const
{
  require(n_sections >= 1, "Line/Number of sections", n_sections, "must be >= 1");
  if (!is_line())
    return;
  const unsigned int n = section.number_of_spans(), o = overlap_spans;
  require(o >= 1, "Line/Overlap spans", o,
          "an overlap shorter than one span; allowed: 1 .. " + std::to_string(n / 2) +
              " spans of the section's " + std::to_string(n));
  require(2 * o <= n, "Line/Overlap spans", o,
          "section 3's anchor would lie inside section 1 (" + std::to_string(n) +
              " spans each); allowed: at most " + std::to_string(n / 2));
  require(overlap_heights.size() == o + 1, "Line/Overlap heights",
          list_to_string(overlap_heights),
          "one height per overlap support (" + std::to_string(o + 1) + ")");
  const std::vector<double> l = section.spans();
  const std::vector<double> last(l.end() - o, l.end()), first(l.begin(), l.begin() + o);
  require(last == first, "Line/Overlap spans", o,
          "the overlap's supports do not coincide: the section's last spans (" +
              list_to_string(last) + ") m differ from its first (" +
              list_to_string(first) + ") m");
}
} // namespace pantocat
