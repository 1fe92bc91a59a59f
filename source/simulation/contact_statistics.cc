#include <pantocat/analysis/butterworth_low_pass.h>
#include <pantocat/base/input_error.h>
#include <pantocat/base/serialization.h>
#include <pantocat/simulation/contact_statistics.h>
#include <pantocat/space/catenary_discretisation.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pantocat
{
namespace
{
/// Steady arms at a window's end count as inside: a nanometre of tolerance
/// for positions summed from span lengths against a window typed in metres.
constexpr double position_tolerance = 1e-9;

/// The indices of the time points whose x_p lies in @p window.
std::vector<std::size_t> points_in(const std::vector<double>& x_p,
                                   const EvaluationWindow& window)
{
  std::vector<std::size_t> points;
  for (std::size_t n = 0; n < x_p.size(); ++n)
    if (window.contains(x_p[n]))
      points.push_back(n);
  return points;
}

/// lambda_p through the zero-phase low pass; sample rate from the time points.
std::vector<double> low_passed(const ContactForceSeries& s, const StatisticsParameters& p)
{
  const double sample_rate = (s.t.size() - 1) / (s.t.back() - s.t.front());
  return ButterworthLowPass(p.low_pass_cutoff, sample_rate, p.low_pass_order)
      .filter_forward_backward(s.lambda_p);
}
} // namespace

ForceFigures force_figures(const std::vector<double>& force,
                           const std::vector<std::size_t>& points)
{
  ForceFigures r;
  r.n_points = points.size();
  if (points.empty()) // a window narrower than one step: nothing to report
  {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    r.mean = r.std = r.max = r.min = r.mean_plus_3std = r.mean_minus_3std = nan;
    r.contact_loss_percent = nan;
    return r;
  }
  double sum = 0.;
  unsigned long without_force = 0;
  r.max = -std::numeric_limits<double>::infinity();
  r.min = std::numeric_limits<double>::infinity();
  for (const std::size_t n : points)
  {
    sum += force[n];
    r.max = std::max(r.max, force[n]);
    r.min = std::min(r.min, force[n]);
    without_force += force[n] <= 0. ? 1 : 0;
  }
  r.mean = sum / r.n_points;
  double sum_sq = 0.;
  for (const std::size_t n : points)
    sum_sq += (force[n] - r.mean) * (force[n] - r.mean);
  r.std = std::sqrt(sum_sq / r.n_points);
  r.mean_plus_3std = r.mean + 3. * r.std;
  r.mean_minus_3std = r.mean - 3. * r.std;
  r.contact_loss_percent = 100. * without_force / r.n_points;
  return r;
}

std::optional<double> ContactForceStatistics::max_steady_arm_uplift() const
{
  if (steady_arms.empty())
    return std::nullopt;
  double largest = -std::numeric_limits<double>::infinity();
  for (const SteadyArmUplift& s : steady_arms)
    largest = std::max(largest, s.max_uplift);
  return largest;
}

ContactForceStatistics evaluate_contact_force(const ContactForceSeries& s,
                                              const StatisticsParameters& p,
                                              const EvaluationWindow& window,
                                              std::vector<double>* filtered)
{
  ContactForceStatistics r;
  r.window = window;
  const std::vector<std::size_t> points = points_in(s.x_p, window);
  r.raw = force_figures(s.lambda_p, points);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  r.first_position = points.empty() ? nan : s.x_p[points.front()];
  r.last_position = points.empty() ? nan : s.x_p[points.back()];
  r.first_time = points.empty() ? nan : s.t[points.front()];
  r.last_time = points.empty() ? nan : s.t[points.back()];
  std::vector<double> force = s.lambda_p;
  if (p.low_pass_cutoff > 0. && s.t.size() > 2)
  {
    force = low_passed(s, p);
    r.filter_cutoff_hz = p.low_pass_cutoff;
    r.filter_order = p.low_pass_order;
    r.filtered = force_figures(force, points);
  }
  if (filtered)
    *filtered = std::move(force);
  return r;
}

ContactStatistics::ContactStatistics(const StatisticsParameters& parameters,
                                     const CatenaryDiscretisation& d,
                                     const SemiDiscreteSystem& system,
                                     const std::vector<double>& steady_arm_positions,
                                     const unsigned int pantograph)
    : parameters(parameters),
      window(parameters.evaluation_window(d.catenary_parameters().support_positions())),
      pantograph(pantograph)
{
  if (!system.has_block("contact wire")) // a rigid wire: no uplift to measure
    return;
  for (const double x : d.catenary_parameters().dropper_positions)
    wire_rows.push_back(wire_point_row(d, system, Wire::contact_wire, x));
  n_droppers = wire_rows.size();
  for (const double x : steady_arm_positions)
    if (window.contains(x, position_tolerance))
    {
      steady_arms.push_back(x);
      wire_rows.push_back(wire_point_row(d, system, Wire::contact_wire, x));
    }
}

ContactStatistics::ContactStatistics(const StatisticsParameters& parameters,
                                     const std::vector<double>& supports,
                                     const UpliftPoints& points,
                                     const unsigned int pantograph,
                                     const unsigned int wire)
    : parameters(parameters), window(parameters.evaluation_window(supports)),
      pantograph(pantograph), wire(wire), wire_rows(points.droppers),
      n_droppers(points.droppers.size())
{
  for (unsigned int k = 0; k < points.steady_arms.size(); ++k)
    if (window.contains(points.steady_arm_positions[k], position_tolerance))
    {
      steady_arms.push_back(points.steady_arm_positions[k]);
      wire_rows.push_back(points.steady_arms[k]);
    }
}

void ContactStatistics::start(const SimulationLayout& layout)
{
  contact = layout.pantographs.at(pantograph);
  if (wire != all_wires) // one contact wire's share
    contact.wire_contacts = {contact.wire_contacts.at(wire)};
  if (layout.dropper_indices.empty() && n_droppers > 0) // a scene without droppers
  {
    wire_rows.erase(wire_rows.begin(), wire_rows.begin() + n_droppers);
    n_droppers = 0;
  }
  recorded = {};
  passed_points = 0;
  passed_uplift.clear();
  left_window_at = -1.;
  initial_height.clear();
  max_uplift.assign(wire_rows.size(), -std::numeric_limits<double>::infinity());
}

void ContactStatistics::observe_state(const TimePoint& point, const DynamicState& state)
{
  recorded.t.push_back(point.t);
  recorded.x_p.push_back(point.x_p[pantograph]);
  recorded.lambda_p.push_back(contact_force(contact, point));
  recorded.in_contact.push_back(in_contact(contact, point));
  const bool first = initial_height.empty();
  for (std::size_t j = 0; j < wire_rows.size(); ++j)
  {
    const double w = wire_rows[j].dot(state.q);
    if (first)
      initial_height.push_back(w);
    max_uplift[j] = std::max(max_uplift[j], w - initial_height[j]);
  }
  remember_passed_window();
}

void ContactStatistics::remember_passed_window()
{
  if (passed_points > 0 || window.whole_run() || recorded.x_p.back() <= window.end)
    return;
  if (left_window_at <
      0.) // once: the first time point past the window (also after a resume)
  {
    const auto left = std::find_if(recorded.x_p.begin(), recorded.x_p.end(),
                                   [&](const double x) { return x > window.end; });
    left_window_at = recorded.t[left - recorded.x_p.begin()];
  }
  if (recorded.t.back() >= left_window_at + passed_window_margin)
  {
    passed_points = recorded.t.size();
    passed_uplift = max_uplift;
  }
}

std::optional<ContactForceStatistics> ContactStatistics::passed_window() const
{
  if (passed_points == 0)
    return std::nullopt;
  ContactForceSeries cut;
  cut.t.assign(recorded.t.begin(), recorded.t.begin() + passed_points);
  cut.x_p.assign(recorded.x_p.begin(), recorded.x_p.begin() + passed_points);
  cut.lambda_p.assign(recorded.lambda_p.begin(),
                      recorded.lambda_p.begin() + passed_points);
  cut.in_contact.assign(recorded.in_contact.begin(),
                        recorded.in_contact.begin() + passed_points);
  ContactForceStatistics s = evaluate_contact_force(cut, parameters, window);
  s.max_uplift_at_droppers.assign(passed_uplift.begin(),
                                  passed_uplift.begin() + n_droppers);
  for (std::size_t k = 0; k < steady_arms.size(); ++k)
    s.steady_arms.push_back({steady_arms[k], passed_uplift[n_droppers + k]});
  return s;
}

void ContactStatistics::finish()
{
  statistics = evaluate_contact_force(recorded, parameters, window, &filtered);
  statistics.max_uplift_at_droppers.assign(max_uplift.begin(),
                                           max_uplift.begin() + n_droppers);
  for (std::size_t k = 0; k < steady_arms.size(); ++k)
    statistics.steady_arms.push_back({steady_arms[k], max_uplift[n_droppers + k]});
}

void ContactStatistics::save(CheckpointOut& archive) const
{
  // The whole series: the zero-phase low pass runs over all of it at the end.
  archive << recorded.t << recorded.x_p << recorded.lambda_p << recorded.in_contact
          << initial_height << max_uplift << passed_points << passed_uplift;
}

void ContactStatistics::resume(const SimulationLayout& layout, CheckpointIn& archive)
{
  start(layout);
  archive >> recorded.t >> recorded.x_p >> recorded.lambda_p >> recorded.in_contact >>
      initial_height >> max_uplift >> passed_points >> passed_uplift;
  if (max_uplift.size() != wire_rows.size())
    throw SimulationError("the checkpoint holds the contact wire at " +
                          std::to_string(max_uplift.size()) + " points, this run at " +
                          std::to_string(wire_rows.size()) +
                          " (droppers and steady arms in the window): start afresh");
}
} // namespace pantocat
