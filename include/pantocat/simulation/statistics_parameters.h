#pragma once

#include <deal.II/base/parameter_handler.h>

#include <vector>

namespace pantocat
{
/// Subsection Statistics: how the contact-force statistics of a run are evaluated.
struct StatisticsParameters
{
  /// Cut-off f_c [Hz] of the zero-phase Butterworth low pass; 0: no filter.
  double low_pass_cutoff = 0.;
  /// The window [x0, x1] of pantograph positions x_p [m]; empty: the whole run.
  std::vector<double> window;

  static void declare_parameters(dealii::ParameterHandler& prm);
  void parse_parameters(dealii::ParameterHandler& prm);
  /**
   * Cross-checks with the run: the cut-off below the Nyquist frequency
   * 1/(2 dt), the window x0 < x1 overlapping [x_p(0), final position];
   * throws InputError.
   */
  void check(double time_step, double initial_position, double final_position) const;
};
} // namespace pantocat
