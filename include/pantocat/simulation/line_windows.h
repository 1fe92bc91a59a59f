#pragma once

#include <pantocat/simulation/contact_statistics.h>

#include <memory>
#include <string>
#include <vector>

namespace pantocat
{
class CaseRunner;

/**
 * The evaluations a line of several tension sections adds to the run's
 * window: for every pantograph in contact, each overlap (O_0 to O_o) with
 * the force on all contact wires and on each wire that runs through it, and
 * the run's window per contact wire when more than one runs through it.
 * Each is a ContactStatistics observer (raw and low-passed figures; the
 * uplift at the steady arms of the overlap). A single section adds nothing.
 */
class LineWindows
{
public:
  struct Evaluation
  {
    unsigned int pantograph = 0; ///< index in SimulationLayout::pantographs
    std::string window;          ///< "window", "overlap 1", ...
    std::string wire;            ///< "all wires" or "section k"
    std::unique_ptr<ContactStatistics> statistics;
  };

  LineWindows(const StatisticsParameters& parameters, const CaseRunner& runner,
              const SimulationLayout& layout);

  /// The observers to attach to the run (none for a single section).
  std::vector<SimulationObserver*> observers() const;
  const std::vector<Evaluation>& evaluations() const { return list; }

private:
  std::vector<Evaluation> list;
};
} // namespace pantocat
