#include <pantocat/simulation/case_runner.h>
#include <pantocat/simulation/line_windows.h>

namespace pantocat
{
namespace
{
/// The sections whose contact wire runs through [x0, x1] for a positive length.
std::vector<unsigned int> wires_through(const std::vector<CatenaryParameters>& sections,
                                        const double x0, const double x1)
{
  std::vector<unsigned int> wires;
  for (unsigned int k = 0; k < sections.size(); ++k)
    if (sections[k].start < x1 && sections[k].start + sections[k].length() > x0)
      wires.push_back(k);
  return wires;
}

/// The steady arms of @p points without the droppers (the run's window records
/// those; each window keeps the arms inside it).
UpliftPoints steady_arms_only(const UpliftPoints& points)
{
  UpliftPoints arms;
  arms.steady_arm_positions = points.steady_arm_positions;
  arms.steady_arms = points.steady_arms;
  return arms;
}
} // namespace

LineWindows::LineWindows(const StatisticsParameters& parameters, const CaseRunner& runner,
                         const SimulationLayout& layout)
{
  const Case& c = runner.case_data();
  if (!c.line.is_line())
    return;
  const std::vector<CatenaryParameters>& sections = runner.sections();
  const UpliftPoints arms = steady_arms_only(runner.uplift_points());
  const std::vector<double> line_ends{0., c.line_length()};
  const auto add = [&](const unsigned int p, const std::string& window,
                       const StatisticsParameters& s, const std::vector<double>& supports,
                       const std::vector<unsigned int>& wires, const bool with_total)
  {
    const std::vector<unsigned int>& own = layout.pantographs[p].wire_contacts;
    if (with_total)
      list.push_back({p, window, "all wires",
                      std::make_unique<ContactStatistics>(s, supports, arms, p)});
    for (const unsigned int k : wires)
      if (k < own.size())
        list.push_back(
            {p, window, sections[k].name,
             std::make_unique<ContactStatistics>(s, supports, UpliftPoints{}, p, k)});
  };
  const std::vector<double> supports = c.window_supports(parameters.window_section);
  const EvaluationWindow regular = parameters.evaluation_window(supports);
  const auto overlaps = c.line.overlaps(c.catenary);
  for (unsigned int p = 0; p < layout.pantographs.size(); ++p)
  {
    if (!layout.pantographs[p].has_contact())
      continue;
    const std::vector<unsigned int> wires =
        wires_through(sections, regular.start, regular.end);
    if (wires.size() > 1)
      add(p, "window", parameters, supports, wires, false);
    for (unsigned int o = 0; o < overlaps.size(); ++o)
    {
      StatisticsParameters s = parameters;
      s.window_spans.clear();
      s.window = {overlaps[o].first, overlaps[o].second};
      add(p, "overlap " + std::to_string(o + 1), s, line_ends,
          wires_through(sections, overlaps[o].first, overlaps[o].second), true);
    }
  }
}

std::vector<SimulationObserver*> LineWindows::observers() const
{
  std::vector<SimulationObserver*> o;
  for (const Evaluation& e : list)
    o.push_back(e.statistics.get());
  return o;
}
} // namespace pantocat
