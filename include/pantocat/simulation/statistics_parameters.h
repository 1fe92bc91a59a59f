#pragma once

#include <deal.II/base/parameter_handler.h>

#include <limits>
#include <string>
#include <vector>

namespace pantocat
{
/**
 * The evaluation window: the pantograph positions x_p in [start, end] (both
 * included) in which the contact-force statistics are taken; given in metres
 * (Statistics/Window), by span numbers (Statistics/Window spans), or the
 * whole run.
 */
struct EvaluationWindow
{
  double start = -std::numeric_limits<double>::infinity(); ///< x [m]
  double end = std::numeric_limits<double>::infinity();    ///< x [m]
  /// The spans first..last (1-based) when given by span numbers; 0 otherwise.
  unsigned int first_span = 0, last_span = 0;

  /// Neither Statistics/Window nor Statistics/Window spans: every time point.
  bool whole_run() const { return start == -std::numeric_limits<double>::infinity(); }
  bool given_by_spans() const { return first_span > 0; }
  /// start - @p tolerance <= @p x <= end + @p tolerance.
  bool contains(double x, double tolerance = 0.) const
  {
    return x >= start - tolerance && x <= end + tolerance;
  }
  /// "x_p in [220, 330] m (spans 5-6)", "x_p in [2, 10] m", "the whole run".
  std::string describe() const;
};

/// Subsection Statistics: how the contact-force statistics of a run are evaluated.
struct StatisticsParameters
{
  /// Cut-off f_c [Hz] of the zero-phase Butterworth low pass; 0: no filter.
  double low_pass_cutoff = 0.;
  /// Order n of the Butterworth low pass (run forwards and backwards: |H|^2).
  unsigned int low_pass_order = 4;
  /// The window [x0, x1] of pantograph positions x_p [m]; empty: not given so.
  std::vector<double> window;
  /// The window as spans: first (and last), 1-based; empty: not given so.
  std::vector<long> window_spans;
  /// On a line: the section (1-based) whose spans Window spans counts and
  /// inside which Window lies.
  unsigned int window_section = 1;
  /// Open intervals of one constraint whose reclosure between them is
  /// shorter than this [s] form one episode (SwitchEpisode); 0: none merged.
  double episode_resolution = 1e-3;

  static void declare_parameters(dealii::ParameterHandler& prm);
  void parse_parameters(dealii::ParameterHandler& prm);
  /**
   * Cross-checks with the run and the section whose supports (the ends of
   * its spans, first to last) are @p supports: the cut-off below the Nyquist
   * frequency 1/(2 dt); not both Window and Window spans; a window x0 < x1
   * inside the section; span numbers in 1..n_spans, first <= last; the window
   * overlapping [x_p(0), final position]. Throws InputError.
   */
  void check(double time_step, double initial_position, double final_position,
             const std::vector<double>& supports) const;
  /**
   * The window in metres: Window as given, or for Window spans = first, last
   * the supports [x_{first-1}, x_last] of @p supports; the whole run if
   * neither is given. Needs check() to have passed.
   */
  EvaluationWindow evaluation_window(const std::vector<double>& supports) const;

private:
  void check_spans(const std::vector<double>& supports) const;
  void check_metres(const std::vector<double>& supports) const;
};
} // namespace pantocat
