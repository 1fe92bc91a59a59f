#pragma once

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace pantocat
{
/// How much a run prints: quiet only errors; normal the summary, statistics and
/// timings (and a progress line on a terminal); detailed also the integrator's
/// counters and every file written.
enum class Verbosity
{
  quiet,
  normal,
  detailed
};

struct OutputParameters
{
  std::string directory = "output";      ///< created if needed
  unsigned int vtu_subdivisions = 4;     ///< sample points per cell in VTU files
  unsigned int time_series_interval = 1; ///< write every k-th time point
  bool plots = true;                     ///< PNG plots with gnuplot, if installed
  bool report = true;                    ///< report.html (run_report.h)
  double vtu_interval = 0.; ///< simulated seconds between VTU frames; 0: none
  Verbosity verbosity = Verbosity::normal;
  std::vector<double> probe_positions; ///< x of the w_w(x) columns [m]
  bool energy = false;                 ///< energy column and range

  static void declare_parameters(dealii::ParameterHandler& prm);
  void parse_parameters(dealii::ParameterHandler& prm);
  /**
   * Checks against the run's time step: a VTU interval in (0, @p time_step)
   * asks for frames closer than the time points there are (and one of
   * 1e-300 s would count frames for ever), and against the wires' domain
   * [0, @p length]: every probe inside it; throws InputError.
   */
  void check(double time_step, double length) const;
};
} // namespace pantocat
