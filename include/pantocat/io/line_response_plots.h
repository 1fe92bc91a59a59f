#pragma once

#include <pantocat/io/plots.h>
#include <pantocat/simulation/assessment.h>
#include <pantocat/simulation/contact_statistics.h>
#include <pantocat/simulation/run_statistics.h>

#include <string>
#include <vector>

namespace pantocat
{
/// What the plots of the line's response along x draw besides their data.
struct LineResponseFrame
{
  std::vector<double> supports; ///< x [m] of the supports (dashed, spans numbered)
  std::string title;            ///< the run's title (method, speed)
};

/**
 * uplift.png and uplift.svg: the largest rise of the contact wire over its
 * static height at every dropper over the whole run (points) and at every
 * steady arm in the evaluation window of @p statistics (impulses), with the
 * window shaded and the steady-arm limit of @p assessment drawn (if it has
 * one). Script uplift.gp, its data inline. Nothing to draw without droppers
 * and steady arms (no outputs).
 */
PlotScript uplift_script(const std::string& directory,
                         const ContactForceStatistics& statistics,
                         const std::vector<double>& dropper_positions,
                         const Assessment* assessment, const LineResponseFrame& frame);

/**
 * dropper_slack.png and dropper_slack.svg: per dropper at its position, the
 * time it was slack in the whole run [ms] (impulses) and the number of its
 * slack intervals (points, right axis), the evaluation @p window shaded.
 * Script dropper_slack.gp, its data inline. No outputs without droppers.
 */
PlotScript dropper_slack_script(const std::string& directory,
                                const std::vector<double>& dropper_positions,
                                const std::vector<std::vector<Interval>>& slack,
                                const EvaluationWindow& window,
                                const LineResponseFrame& frame);
} // namespace pantocat
