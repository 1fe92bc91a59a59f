#pragma once

#include <vector>

namespace pantocat
{
/// Errors of a time series y(t) against a reference series y_ref(t_ref).
struct SeriesErrors
{
  double l2 = 0.;  ///< (1/T int_0^T e^2 dt)^(1/2) (trapezoidal rule on the run's grid)
  double max = 0.; ///< max_i |e(t_i)|
  double relative_max = 0.;  ///< max / max_t |y_ref|
  double relative_peak = 0.; ///< |max y - max y_ref| / |max y_ref|
  /// True if some t_i is not a reference time point (the steps do not divide
  /// each other): y_ref was interpolated linearly there.
  bool interpolated = false;
};

/**
 * Compares y at the run's own time points t_i (within the reference's time
 * interval) with the reference. Where t_i is a time point of the reference
 * (the reference's step divides the run's) the value is taken as is;
 * otherwise y_ref is interpolated linearly, which adds an O(dt_ref^2) error.
 */
SeriesErrors compare_series(const std::vector<double>& t, const std::vector<double>& y,
                            const std::vector<double>& t_ref,
                            const std::vector<double>& y_ref);

/// Errors of a profile w(x_j) against w_ref(x_j) on the same equidistant points.
struct ProfileErrors
{
  double l2 = 0.; ///< ||e||_L2 [m sqrt(m)] (trapezoidal rule)
  double h1 = 0.; ///< |e|_H1 [sqrt(m)]: the slopes of the piecewise linear interpolant
};

ProfileErrors compare_profiles(const std::vector<double>& w,
                               const std::vector<double>& w_ref, double length);
} // namespace pantocat
