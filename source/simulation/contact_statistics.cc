#include <pantocat/analysis/butterworth_low_pass.h>
#include <pantocat/base/serialization.h>
#include <pantocat/simulation/contact_statistics.h>
#include <pantocat/space/catenary_discretisation.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pantocat
{
ContactForceStatistics evaluate_contact_force(const ContactForceSeries& s,
                                              const StatisticsParameters& p,
                                              std::vector<double>* filtered)
{
  ContactForceStatistics r;
  std::vector<double> force = s.lambda_p;
  if (p.low_pass_cutoff > 0. && s.t.size() > 2)
  {
    const double sample_rate = (s.t.size() - 1) / (s.t.back() - s.t.front());
    force =
        ButterworthLowPass(p.low_pass_cutoff, sample_rate).filter_forward_backward(force);
    r.filter_cutoff_hz = p.low_pass_cutoff;
  }
  if (filtered)
    *filtered = force;
  const double x0 =
      p.window.empty() ? -std::numeric_limits<double>::infinity() : p.window[0];
  const double x1 =
      p.window.empty() ? std::numeric_limits<double>::infinity() : p.window[1];
  double sum = 0., sum_sq = 0.;
  unsigned long without_contact = 0;
  r.max = -std::numeric_limits<double>::infinity();
  r.min = std::numeric_limits<double>::infinity();
  for (std::size_t n = 0; n < force.size(); ++n)
  {
    if (s.x_p[n] < x0 || s.x_p[n] > x1)
      continue;
    if (r.n_points == 0)
      r.window_start = s.x_p[n];
    r.window_end = s.x_p[n];
    ++r.n_points;
    sum += force[n];
    r.max = std::max(r.max, force[n]);
    r.min = std::min(r.min, force[n]);
    without_contact += s.in_contact[n] ? 0 : 1;
  }
  if (r.n_points == 0) // a window narrower than one step: nothing to report
  {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    r.mean = r.std = r.mean_minus_3_sigma = r.mean_plus_3_sigma = nan;
    r.max = r.min = r.percent_without_contact = r.window_start = r.window_end = nan;
    return r;
  }
  r.mean = sum / r.n_points;
  // Two passes over the window: no cancellation in the variance.
  for (std::size_t n = 0; n < force.size(); ++n)
    if (s.x_p[n] >= x0 && s.x_p[n] <= x1)
      sum_sq += (force[n] - r.mean) * (force[n] - r.mean);
  r.std = std::sqrt(sum_sq / r.n_points);
  r.mean_minus_3_sigma = r.mean - 3. * r.std;
  r.mean_plus_3_sigma = r.mean + 3. * r.std;
  r.percent_without_contact = 100. * without_contact / r.n_points;
  return r;
}

ContactStatistics::ContactStatistics(const StatisticsParameters& parameters,
                                     const CatenaryDiscretisation& d,
                                     const SemiDiscreteSystem& system,
                                     const unsigned int pantograph)
    : parameters(parameters), pantograph(pantograph)
{
  if (!system.has_block("contact wire")) // a rigid wire: no uplift to measure
    return;
  for (const double x : d.catenary_parameters().dropper_positions)
    dropper_rows.push_back(wire_point_row(d, system, Wire::contact_wire, x));
}

void ContactStatistics::start(const SimulationLayout& layout)
{
  contact_index = layout.pantographs.at(pantograph).contact;
  if (layout.dropper_indices.empty()) // a scene without droppers
    dropper_rows.clear();
  recorded = {};
  initial_height.clear();
  max_uplift.assign(dropper_rows.size(), -std::numeric_limits<double>::infinity());
}

void ContactStatistics::observe_state(const TimePoint& point, const DynamicState& state)
{
  recorded.t.push_back(point.t);
  recorded.x_p.push_back(point.x_p[pantograph]);
  recorded.lambda_p.push_back(point.lambda[contact_index]);
  recorded.in_contact.push_back(point.active[contact_index]);
  const bool first = initial_height.empty();
  for (std::size_t j = 0; j < dropper_rows.size(); ++j)
  {
    const double w = dropper_rows[j].dot(state.q);
    if (first)
      initial_height.push_back(w);
    max_uplift[j] = std::max(max_uplift[j], w - initial_height[j]);
  }
}

void ContactStatistics::finish()
{
  statistics = evaluate_contact_force(recorded, parameters, &filtered);
  statistics.max_uplift_at_droppers = max_uplift;
}

void ContactStatistics::save(CheckpointOut& archive) const
{
  // The whole series: the zero-phase low pass runs over all of it at the end.
  archive << recorded.t << recorded.x_p << recorded.lambda_p << recorded.in_contact
          << initial_height << max_uplift;
}

void ContactStatistics::resume(const SimulationLayout& layout, CheckpointIn& archive)
{
  contact_index = layout.pantographs.at(pantograph).contact;
  archive >> recorded.t >> recorded.x_p >> recorded.lambda_p >> recorded.in_contact >>
      initial_height >> max_uplift;
}
} // namespace pantocat
