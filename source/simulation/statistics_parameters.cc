#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>
#include <pantocat/simulation/statistics_parameters.h>

#include <deal.II/base/utilities.h>

namespace pantocat
{
std::string EvaluationWindow::describe() const
{
  if (whole_run())
    return "the whole run";
  std::string text =
      "x_p in [" + number_to_string(start, 6) + ", " + number_to_string(end, 6) + "] m";
  if (given_by_spans())
    text += first_span == last_span ? " (span " + std::to_string(first_span) + ")"
                                    : " (spans " + std::to_string(first_span) + "-" +
                                          std::to_string(last_span) + ")";
  return text;
}

void StatisticsParameters::declare_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Statistics");
  prm.declare_entry("Low-pass cut-off", "0", dealii::Patterns::Double(0.),
                    "Cut-off frequency f_c [Hz] of the zero-phase low pass (Butterworth "
                    "of Low-pass order, run forward and backward: -6 dB at f_c) applied "
                    "to the contact force of the whole run before the window is taken; "
                    "0: unfiltered (only the raw statistics). The railway standards use "
                    "20 Hz.");
  prm.declare_entry("Low-pass order", "4", dealii::Patterns::Integer(1, 8),
                    "Order n of the Butterworth low pass; forward and backward its gain "
                    "is 1/(1 + (f/f_c)^(2n)) (pre-warped: f -> tan(pi f/f_s)), 40 n "
                    "dB/decade. The reference section S55 asks for 4.");
  prm.declare_entry("Window section", "1", dealii::Patterns::Integer(1),
                    "On a line of several tension sections (Line/Number of sections): "
                    "the section whose spans Window spans counts and inside which Window "
                    "lies. The overlaps are evaluated as windows of their own.");
  prm.declare_entry("Window", "",
                    dealii::Patterns::List(dealii::Patterns::Double(), 0, 2),
                    "Pantograph positions x0, x1 [m] (inside the section) between which "
                    "the contact-force statistics are taken; empty: Window spans, or the "
                    "whole run. Not together with Window spans.");
  prm.declare_entry("Window spans", "",
                    dealii::Patterns::List(dealii::Patterns::Integer()),
                    "The evaluation window as span numbers first, last (1-based; one "
                    "number: that span): the pantograph from the support before span "
                    "first to the support after span last, e.g. 5, 6 = [220, 330] m on "
                    "S55; empty: Window, or the whole run. Not together with Window.");
  prm.declare_entry(
      "Episode resolution", "0.001", dealii::Patterns::Double(0., 1.),
      "[s]. Open intervals of one unilateral constraint (contact lost, dropper slack) "
      "whose reclosure between them is shorter than this form one episode: a "
      "cascade of impacts where a dropper and the contact act on one wire point is "
      "resolved event by event, and a finer step resolves more of its ever shorter "
      "intervals; its episode converges. summary.json lists both. Convergence "
      "studies match the events of the episodes at least this long and count the "
      "shorter ones (with their length). 0: every interval is its own episode. The "
      "loss percentage and the force statistics do not depend on it.");
  prm.leave_subsection();
}

void StatisticsParameters::parse_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Statistics");
  low_pass_cutoff = prm.get_double("Low-pass cut-off");
  low_pass_order = prm.get_integer("Low-pass order");
  episode_resolution = prm.get_double("Episode resolution");
  window_section = prm.get_integer("Window section");
  window = dealii::Utilities::string_to_double(
      dealii::Utilities::split_string_list(prm.get("Window")));
  window_spans.clear();
  for (const std::string& s :
       dealii::Utilities::split_string_list(prm.get("Window spans")))
    window_spans.push_back(std::stol(s));
  prm.leave_subsection();
}

void StatisticsParameters::check(const double time_step, const double x_begin,
                                 const double x_end,
                                 const std::vector<double>& supports) const
{
  const double nyquist = 0.5 / time_step;
  require(low_pass_cutoff < nyquist, "Statistics/Low-pass cut-off", low_pass_cutoff,
          "must lie below the Nyquist frequency 1/(2 dt) = " + number_to_string(nyquist) +
              " Hz (or be 0: no filter)");
  require(window.empty() || window_spans.empty(), "Statistics/Window spans",
          list_to_string(window_spans),
          "not together with Statistics/Window = " + list_to_string(window) +
              ": give the evaluation window either by span numbers or in metres");
  if (window.empty() && window_spans.empty())
    return;
  check_spans(supports);
  check_metres(supports);
  const EvaluationWindow w = evaluation_window(supports);
  const bool by_spans = !window_spans.empty();
  require(w.end >= x_begin && w.start <= x_end,
          by_spans ? "Statistics/Window spans" : "Statistics/Window",
          by_spans ? list_to_string(window_spans) : list_to_string(window),
          (by_spans ? "the window x = " + number_to_string(w.start) + " to " +
                          number_to_string(w.end) + " m must"
                    : "must be two positions x0 < x1 [m] that") +
              " overlap the run from x_p = " + number_to_string(x_begin) + " to " +
              number_to_string(x_end) + " m (or be empty: the whole run)");
}

void StatisticsParameters::check_spans(const std::vector<double>& supports) const
{
  if (window_spans.empty())
    return;
  const long n = static_cast<long>(supports.size()) - 1;
  const std::string text = list_to_string(window_spans);
  require(window_spans.size() <= 2, "Statistics/Window spans", text,
          "one span number, or two: the first and the last span of the window");
  for (const long k : window_spans)
    require(k >= 1 && k <= n, "Statistics/Window spans", text,
            "span numbers run from 1 to " + std::to_string(n) + " (the section has " +
                std::to_string(n) + (n == 1 ? " span)" : " spans)"));
  require(window_spans.front() <= window_spans.back(), "Statistics/Window spans", text,
          "first, last with first <= last (1 <= first <= last <= " + std::to_string(n) +
              ")");
}

void StatisticsParameters::check_metres(const std::vector<double>& supports) const
{
  if (window.empty())
    return;
  const std::string text = list_to_string(window);
  require(window.size() == 2 && window[0] < window[1], "Statistics/Window", text,
          "must be two positions x0 < x1 [m] (or be empty: the whole run)");
  require(window[0] >= supports.front() && window[1] <= supports.back(),
          "Statistics/Window", text,
          "must lie inside the section, from x = " + number_to_string(supports.front()) +
              " to " + number_to_string(supports.back()) + " m");
}

EvaluationWindow
StatisticsParameters::evaluation_window(const std::vector<double>& supports) const
{
  EvaluationWindow w;
  if (!window.empty())
  {
    w.start = window[0];
    w.end = window[1];
  }
  else if (!window_spans.empty())
  {
    w.first_span = window_spans.front();
    w.last_span = window_spans.back();
    w.start = supports.at(w.first_span - 1);
    w.end = supports.at(w.last_span);
  }
  return w;
}
} // namespace pantocat
