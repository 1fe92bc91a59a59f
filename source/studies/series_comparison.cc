#include <pantocat/studies/series_comparison.h>

#include <algorithm>
#include <cmath>

namespace pantocat
{
namespace
{
/// y_ref(t), exact at a reference time point, else linear; sets @p interpolated.
double reference_value(const std::vector<double>& t_ref, const std::vector<double>& y_ref,
                       const double t, bool& interpolated)
{
  // Time points accumulate round-off; a millionth of the reference's step is far below
  // it.
  const double tolerance = 1e-6 * (t_ref.back() - t_ref.front()) / (t_ref.size() - 1);
  auto upper = std::lower_bound(t_ref.begin(), t_ref.end(), t - tolerance);
  const std::size_t j = upper - t_ref.begin();
  if (j < t_ref.size() && std::abs(t_ref[j] - t) <= tolerance)
    return y_ref[j];
  interpolated = true;
  const std::size_t i = std::min(std::max<std::size_t>(j, 1), t_ref.size() - 1);
  const double s = (t - t_ref[i - 1]) / (t_ref[i] - t_ref[i - 1]);
  return (1. - s) * y_ref[i - 1] + s * y_ref[i];
}
} // namespace

SeriesErrors compare_series(const std::vector<double>& t, const std::vector<double>& y,
                            const std::vector<double>& t_ref,
                            const std::vector<double>& y_ref)
{
  SeriesErrors e;
  const double t_end = t_ref.back() * (1. + 1e-12);
  double integral = 0., previous_t = 0., previous_e2 = 0., duration = 0.;
  bool first = true;
  for (std::size_t i = 0; i < t.size() && t[i] <= t_end; ++i)
  {
    const double err = y[i] - reference_value(t_ref, y_ref, t[i], e.interpolated);
    e.max = std::max(e.max, std::abs(err));
    if (!first)
    {
      integral += 0.5 * (t[i] - previous_t) * (previous_e2 + err * err);
      duration += t[i] - previous_t;
    }
    previous_t = t[i], previous_e2 = err * err, first = false;
  }
  e.l2 = duration > 0. ? std::sqrt(integral / duration) : e.max;
  double ref_abs_max = 0.;
  for (const double v : y_ref)
    ref_abs_max = std::max(ref_abs_max, std::abs(v));
  const double peak = *std::max_element(y.begin(), y.end());
  const double ref_peak = *std::max_element(y_ref.begin(), y_ref.end());
  e.relative_max = e.max / ref_abs_max;
  e.relative_peak = std::abs(peak - ref_peak) / std::abs(ref_peak);
  return e;
}

ProfileErrors compare_profiles(const std::vector<double>& w,
                               const std::vector<double>& w_ref, const double length)
{
  ProfileErrors e;
  const std::size_t n = w.size() - 1;
  const double h = length / n;
  double l2 = 0., h1 = 0.;
  for (std::size_t j = 0; j < n; ++j)
  {
    const double e0 = w[j] - w_ref[j], e1 = w[j + 1] - w_ref[j + 1];
    l2 += 0.5 * h * (e0 * e0 + e1 * e1);
    h1 += (e1 - e0) * (e1 - e0) / h;
  }
  e.l2 = std::sqrt(l2);
  e.h1 = std::sqrt(h1);
  return e;
}
} // namespace pantocat
