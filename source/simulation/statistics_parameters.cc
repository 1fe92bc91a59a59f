#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>
#include <pantocat/simulation/statistics_parameters.h>

#include <deal.II/base/utilities.h>

namespace pantocat
{
void StatisticsParameters::declare_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Statistics");
  prm.declare_entry("Low-pass cut-off", "0", dealii::Patterns::Double(0.),
                    "Cut-off frequency f_c [Hz] of the zero-phase low pass (2nd-order "
                    "Butterworth, forward and backward: -6 dB at f_c) applied to the "
                    "contact force before its statistics; 0: unfiltered. The railway "
                    "standards use 20 Hz.");
  prm.declare_entry("Window", "",
                    dealii::Patterns::List(dealii::Patterns::Double(), 0, 2),
                    "Pantograph positions x0, x1 [m] between which the contact-force "
                    "statistics are taken (after filtering the whole run); empty: the "
                    "whole run.");
  prm.leave_subsection();
}

void StatisticsParameters::parse_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Statistics");
  low_pass_cutoff = prm.get_double("Low-pass cut-off");
  window = dealii::Utilities::string_to_double(
      dealii::Utilities::split_string_list(prm.get("Window")));
  prm.leave_subsection();
}

void StatisticsParameters::check(const double time_step, const double x_begin,
                                 const double x_end) const
{
  const double nyquist = 0.5 / time_step;
  require(low_pass_cutoff < nyquist, "Statistics/Low-pass cut-off", low_pass_cutoff,
          "must lie below the Nyquist frequency 1/(2 dt) = " + number_to_string(nyquist) +
              " Hz (or be 0: no filter)");
  if (window.empty())
    return;
  std::string text;
  for (const double x : window)
    text += (text.empty() ? "" : ", ") + number_to_string(x);
  require(window.size() == 2 && window[0] < window[1] && window[1] >= x_begin &&
              window[0] <= x_end,
          "Statistics/Window", text,
          "must be two positions x0 < x1 [m] that overlap the run from x_p = " +
              number_to_string(x_begin) + " to " + number_to_string(x_end) +
              " m (or be empty: the whole run)");
}
} // namespace pantocat
