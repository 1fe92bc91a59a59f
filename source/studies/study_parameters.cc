#include <pantocat/base/input_error.h>
#include <pantocat/base/safe_files.h>
#include <pantocat/studies/study_parameters.h>
#include <pantocat/time/integrator_registry.h>

#include <deal.II/base/utilities.h>

#include <algorithm>

namespace pantocat
{
using dealii::Patterns::List;
using dealii::Patterns::Selection;

void StudyParameters::declare_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Study");
  prm.declare_entry("Number of intervals", "", List(dealii::Patterns::Integer(1), 0),
                    "Refinements N+1 of the study, coarse to fine (Mode = convergence "
                    "study | work precision). Paired entry by entry with the time "
                    "steps; one entry is used for every refinement; empty: "
                    "Discretisation/Number of intervals.");
  prm.declare_entry("Time steps", "", List(dealii::Patterns::Double(0.), 0),
                    "Time steps dt [s] of the study, coarse to fine, paired with the "
                    "numbers of intervals; empty: Time integration/Time step.");
  prm.declare_entry("Refinements", "paired", Selection("paired|all combinations"),
                    "paired: run (N+1_k, dt_k) for each k (a convergence study); all "
                    "combinations: every N+1 with every dt (work precision only).");
  prm.declare_entry("Discretisations", "", List(Selection("fem|fdm"), 0),
                    "Space discretisations to study (each with every integrator); "
                    "empty: Discretisation/Method.");
  prm.declare_entry("Integrators", "", List(Selection(integrator_selection()), 0),
                    "Time integrators to study; empty: Time integration/Integrator. "
                    "Half-explicit runs with dt above 2/omega_max are skipped and "
                    "reported.");
  prm.declare_entry("Contact laws", "",
                    List(Selection("unilateral|bilateral|penalty"), 0),
                    "Contact laws of the pantographs to study (each with every "
                    "discretisation and integrator): unilateral (rigid), bilateral or "
                    "penalty (with Scene/Contact stiffness and Scene/Contact damping, "
                    "whatever Scene/Contact is); the law is set for every pantograph. "
                    "Empty: Scene/Contact.");
  prm.declare_entry("Reference", "finest run", Selection("finest run|separate run"),
                    "Errors against the finest (last) refinement of each method, or "
                    "against one separate reference run (required in work "
                    "precision mode).");
  prm.declare_entry("Reference discretisation", "fem", Selection("fem|fdm"),
                    "Discretisation of the separate reference run.");
  prm.declare_entry("Reference integrator", "bdf2", Selection(integrator_selection()),
                    "Integrator of the separate reference run.");
  prm.declare_entry("Reference number of intervals", "1000", dealii::Patterns::Integer(1),
                    "N+1 of the separate reference run.");
  prm.declare_entry("Reference time step", "1e-5", dealii::Patterns::Double(0.),
                    "dt [s] of the separate reference run.");
  prm.declare_entry(
      "Quantities", "lambda_p, wire, eigenfrequencies",
      List(Selection("lambda_p|wire|eigenfrequencies|contact statistics"), 1),
      "Convergence study: the errors against the reference of lambda_p over time "
      "(L2 and max norm; with any of lambda_p, wire, eigenfrequencies), of the "
      "contact wire at the final time (L2 and H1) and of the lowest eigenfrequency "
      "of each wire; contact statistics: per run pantograph 1's contact loss [%] and "
      "its low-passed max, min and std in the window of subsection Statistics, the "
      "smallest force of any unilateral constraint, the switch events and their "
      "times, and the successive differences between runs with observed orders "
      "(<name>_contact.txt, .csv; needs no reference).");
  prm.declare_entry("Target relative error", "0.01", dealii::Patterns::Double(0.),
                    "Work precision: report the cheapest run of each method whose "
                    "relative error in lambda_p (max norm, and in max lambda_p) is "
                    "at most this.");
  prm.declare_entry("Output name", "", dealii::Patterns::Anything(),
                    "Base name of the tables and the plot: 1 to 64 letters, digits, "
                    "'-', '_' and '.', not starting with '.' or '-'; empty: "
                    "convergence or work_precision.");
  prm.leave_subsection();
}

void StudyParameters::parse_penalty(dealii::ParameterHandler& prm)
{
  penalty = {};
  if (std::find(contact_laws.begin(), contact_laws.end(), "penalty") ==
      contact_laws.end())
    return;
  prm.enter_subsection("Scene");
  penalty = {prm.get_double("Contact stiffness"), prm.get_double("Contact damping")};
  prm.leave_subsection();
  require(penalty.stiffness > 0., "Scene/Contact stiffness", penalty.stiffness,
          "must be > 0 with Study/Contact laws = penalty");
  require(penalty.damping >= 0., "Scene/Contact damping", penalty.damping,
          "must be >= 0");
}

void StudyParameters::parse_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Study");
  using dealii::Utilities::split_string_list;
  const std::string n_text = prm.get("Number of intervals");
  const std::string dt_text = prm.get("Time steps");
  n_intervals.clear();
  for (const auto& s : split_string_list(n_text))
    n_intervals.push_back(dealii::Utilities::string_to_int(s));
  time_steps.clear();
  for (const auto& s : split_string_list(dt_text))
    time_steps.push_back(dealii::Utilities::string_to_double(s));
  discretisations.clear();
  for (const auto& s : split_string_list(prm.get("Discretisations")))
    discretisations.push_back(space_method_from_string(s));
  integrators.clear();
  for (const auto& s : split_string_list(prm.get("Integrators")))
    integrators.push_back(s);
  all_combinations = prm.get("Refinements") == "all combinations";
  reference = prm.get("Reference") == "separate run" ? StudyReference::separate_run
                                                     : StudyReference::finest_run;
  reference_discretisation =
      space_method_from_string(prm.get("Reference discretisation"));
  reference_integrator = prm.get("Reference integrator");
  reference_n_intervals = prm.get_integer("Reference number of intervals");
  reference_time_step = prm.get_double("Reference time step");
  contact_laws = split_string_list(prm.get("Contact laws"));
  const std::string q = prm.get("Quantities");
  wire_errors = q.find("wire") != std::string::npos;
  eigenfrequency_errors = q.find("eigenfrequencies") != std::string::npos;
  contact_statistics = q.find("contact statistics") != std::string::npos;
  error_table =
      q.find("lambda_p") != std::string::npos || wire_errors || eigenfrequency_errors;
  target_relative_error = prm.get_double("Target relative error");
  output_name = prm.get("Output name");
  prm.leave_subsection();
  parse_penalty(prm);

  for (const double dt : time_steps)
    require(dt > 0., "Study/Time steps", dt, "every step must be > 0");
  require(reference_time_step > 0., "Study/Reference time step", reference_time_step,
          "must be > 0");
  const std::size_t n = std::max(n_intervals.size(), time_steps.size());
  require(all_combinations || n_intervals.size() <= 1 || n_intervals.size() == n,
          "Study/Number of intervals", n_text,
          "give one value or as many as Study/Time steps (" + std::to_string(n) + ")");
  require(all_combinations || time_steps.size() <= 1 || time_steps.size() == n,
          "Study/Time steps", dt_text,
          "give one value or as many as Study/Number of intervals (" + std::to_string(n) +
              ")");
  require_output_name("Study/Output name", output_name);
}
} // namespace pantocat
