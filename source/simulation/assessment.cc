#include <pantocat/base/number_format.h>
#include <pantocat/simulation/assessment.h>

#include <cmath>

namespace pantocat
{
void AssessmentCriteria::declare_parameters(dealii::ParameterHandler& prm)
{
  using dealii::Patterns::Double;
  const AssessmentCriteria d;
  prm.enter_subsection("Assessment");
  prm.declare_entry(
      "Enabled", "true", dealii::Patterns::Bool(),
      "Assess each pantograph's evaluation window (Statistics/Window or "
      "Window spans) by the criteria below. Defaults: EN 50367 / TSI "
      "Energy for AC lines as commonly quoted; check them against your copy "
      "of the standard.");
  prm.declare_entry("Mean force a", number_to_string(d.mean_force_a), Double(0.),
                    "a [N h^2/km^2] of the target mean force F_m <= a v^2 + b, v in km/h "
                    "(AC: 0.00097; DC 3 kV: 0.00228; DC 1.5 kV: 0.00097).");
  prm.declare_entry("Mean force b", number_to_string(d.mean_force_b), Double(0.),
                    "b [N] of the target mean force (AC: 70; DC 3 kV: 90; DC 1.5 kV: "
                    "140).");
  prm.declare_entry("Maximum sigma ratio", number_to_string(d.max_sigma_ratio),
                    Double(0.), "The standard deviation sigma <= this times F_m (0.3).");
  prm.declare_entry("Minimum statistical force",
                    number_to_string(d.min_statistical_force), Double(),
                    "F_m - 3 sigma must exceed this [N] (0: the contact is kept).");
  prm.declare_entry("Maximum contact force", number_to_string(d.max_contact_force),
                    Double(0.),
                    "F_max <= this [N] (350 N: AC above 200 km/h); 0: not assessed.");
  prm.declare_entry("Maximum steady arm uplift",
                    number_to_string(d.max_steady_arm_uplift), Double(0.),
                    "The uplift of the contact wire at a steady arm in the window <= "
                    "this [m]: the line's own value (EN 50119 provides twice the "
                    "simulated uplift as space); 0: not assessed.");
  prm.declare_entry("Maximum contact loss", number_to_string(d.max_contact_loss),
                    Double(0., 100.),
                    "The share of the window's time without contact <= this [%] (0.2: "
                    "the arcing rate NQ of EN 50367, applied to contact loss).");
  prm.leave_subsection();
}

void AssessmentCriteria::parse_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Assessment");
  enabled = prm.get_bool("Enabled");
  mean_force_a = prm.get_double("Mean force a");
  mean_force_b = prm.get_double("Mean force b");
  max_sigma_ratio = prm.get_double("Maximum sigma ratio");
  min_statistical_force = prm.get_double("Minimum statistical force");
  max_contact_force = prm.get_double("Maximum contact force");
  max_steady_arm_uplift = prm.get_double("Maximum steady arm uplift");
  max_contact_loss = prm.get_double("Maximum contact loss");
  prm.leave_subsection();
}

bool Assessment::passed() const
{
  for (const CriterionResult& c : criteria)
    if (!c.passed)
      return false;
  return true;
}

namespace
{
CriterionResult criterion(const std::string& name, const std::string& quantity,
                          const std::string& unit, const double value, const double limit,
                          const bool at_most, const std::string& rule)
{
  const bool passed = at_most ? value <= limit : value > limit;
  return {name, quantity, unit, value, limit, at_most, rule, passed};
}
} // namespace

Assessment assess(const ContactForceStatistics& statistics, const double speed,
                  const AssessmentCriteria& criteria)
{
  Assessment a;
  a.speed_kmh = 3.6 * speed;
  const ForceFigures& f = statistics.filtered ? *statistics.filtered : statistics.raw;
  a.basis = statistics.filtered ? number_to_string(statistics.filter_cutoff_hz) + " Hz"
                                : std::string("raw");
  if (!std::isfinite(f.mean))
    return a; // no time point in the window
  const double v = a.speed_kmh;
  const double target = criteria.mean_force_a * v * v + criteria.mean_force_b;
  a.criteria.push_back(
      criterion("mean_force", "mean force F_m", "N", f.mean, target, true,
                number_to_string(criteria.mean_force_a) + " v^2 + " +
                    number_to_string(criteria.mean_force_b) + " N at " +
                    number_to_string(std::round(10. * v) / 10.) + " km/h"));
  a.criteria.push_back(criterion("sigma", "standard deviation sigma", "N", f.std,
                                 criteria.max_sigma_ratio * f.mean, true,
                                 number_to_string(criteria.max_sigma_ratio) + " F_m"));
  a.criteria.push_back(criterion("statistical_minimum", "F_m - 3 sigma", "N",
                                 f.mean_minus_3std, criteria.min_statistical_force, false,
                                 "Assessment/Minimum statistical force"));
  if (criteria.max_contact_force > 0.)
    a.criteria.push_back(criterion("max_force", "maximum force", "N", f.max,
                                   criteria.max_contact_force, true,
                                   "Assessment/Maximum contact force"));
  if (criteria.max_steady_arm_uplift > 0. && statistics.max_steady_arm_uplift())
    a.criteria.push_back(criterion("steady_arm_uplift", "uplift at the steady arms", "m",
                                   *statistics.max_steady_arm_uplift(),
                                   criteria.max_steady_arm_uplift, true,
                                   "Assessment/Maximum steady arm uplift"));
  a.criteria.push_back(criterion("contact_loss", "contact loss (raw force)", "%",
                                 statistics.raw.contact_loss_percent,
                                 criteria.max_contact_loss, true,
                                 "Assessment/Maximum contact loss"));
  return a;
}
} // namespace pantocat
