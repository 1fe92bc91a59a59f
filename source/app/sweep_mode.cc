#include <pantocat/app/parameter_input.h>
#include <pantocat/app/sweep_mode.h>
#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>
#include <pantocat/scene/steady_arms.h>
#include <pantocat/simulation/catenary_design.h>
#include <pantocat/simulation/checkpoint.h>
#include <pantocat/studies/sweep_study.h>

#include <deal.II/base/patterns.h>
#include <deal.II/base/utilities.h>

#include <boost/property_tree/ptree.hpp>

#include <algorithm>
#include <memory>
#include <regex>
#include <sstream>

namespace pantocat
{
namespace
{
/**
 * The unit of entry @p path ("Catenary/Contact wire/Tension" -> "N"): the
 * first short bracket of its documentation ("Tensile force T [N], > 0."), or
 * "" without one.
 */
std::string unit_of(const dealii::ParameterHandler& prm, const std::string& path)
{
  const boost::property_tree::ptree tree = parameter_tree(prm);
  const auto doc = tree.get_optional<std::string>(
      boost::property_tree::ptree::path_type(path + "/documentation", '/'));
  static const std::regex bracket("\\[([^\\]\\[]{1,12})\\]");
  std::smatch m;
  return doc && std::regex_search(*doc, m, bracket) ? m[1].str() : "";
}

/// The entry @p path ("A/B/Name") of the JSON form of @p tree, if declared.
const boost::property_tree::ptree* find_entry(const boost::property_tree::ptree& tree,
                                              const std::string& path)
{
  const boost::property_tree::ptree* node = &tree;
  for (const std::string& part : dealii::Utilities::split_string_list(path, '/'))
  {
    const auto child = node->find(part);
    if (child == node->not_found())
      return nullptr;
    node = &child->second;
  }
  return node->get_optional<std::string>("pattern_description") ? node : nullptr;
}

/**
 * False for the entries whose value cannot change a sweep's rows: the
 * outputs, checkpoints, the settings of other modes (convergence and
 * work-precision studies, eigenfrequencies, the static elasticity check) and
 * Sweep/Resume, Output name and Stop after runs.
 */
bool sweep_reads(const std::string& entry)
{
  for (const char* prefix :
       {"Output/", "Checkpoint/", "Study/", "Eigenfrequencies/", "Elasticity/"})
    if (entry.rfind(prefix, 0) == 0)
      return false;
  for (const char* name : {"Sweep/Resume", "Sweep/Output name", "Sweep/Stop after runs"})
    if (entry == name)
      return false;
  return true;
}

/// Checks one swept entry (@p which: "Parameter" or "Second parameter") and its values.
void check_entry(const boost::property_tree::ptree& tree, const std::string& which,
                 const std::string& values_name, const std::string& entry,
                 const std::string& values_text, const std::vector<std::string>& values)
{
  const std::string parameter = "Sweep/" + which;
  const boost::property_tree::ptree* node = find_entry(tree, entry);
  require(node != nullptr, parameter, entry,
          "no such entry; allowed: a numeric entry with its subsections, e.g. "
          "Catenary/Contact wire/Tension (pantocat-fem --print-parameters lists them)");
  require(sweep_reads(entry), parameter, entry,
          "the runs of a sweep do not use this entry (outputs, checkpoints and the "
          "settings of other modes cannot change a row); allowed: an entry of the "
          "case, e.g. Catenary/Contact wire/Tension");
  const std::string pattern = node->get<std::string>("pattern_description");
  require(pattern.rfind("[Double", 0) == 0 || pattern.rfind("[Integer", 0) == 0,
          parameter, entry,
          "not a numeric entry (its values are " + pattern +
              "); allowed: an entry whose values are Double or Integer");
  const auto matcher = dealii::Patterns::pattern_factory(pattern);
  for (const std::string& v : values)
    require(matcher->match(v), "Sweep/" + values_name, values_text,
            "the value " + v + " is not allowed for " + entry + ", whose values are " +
                pattern);
}

/// The case and evaluation of one run: the input read again with @p settings.
SweepCase read_run(const SweepInput& input, const std::vector<std::string>& settings)
{
  std::vector<std::string> overrides = input.overrides;
  overrides.insert(overrides.end(), settings.begin(), settings.end());
  dealii::ParameterHandler prm;
  read_program_parameters(prm, input.file, overrides);
  ProgramParameters p;
  p.parse_parameters(prm);
  const Case c = p.make_case();
  c.check_dynamics();
  return {c, p.statistics};
}

/// The settings of a speed sweep's run: every pantograph at @p kmh.
std::vector<std::string> speed_settings(const ProgramParameters& p, const double kmh)
{
  const std::string v = number_to_string(kmh / 3.6, 17);
  std::vector<std::string> settings = {"Pantograph/Speed=" + v};
  for (unsigned int k = 2; k <= p.scene.pantographs.size(); ++k)
    settings.push_back("Pantograph " + std::to_string(k) + "/Speed=" + v);
  return settings;
}

/// Steps times N+1: what a run costs, to hand out the longest runs first.
double cost_of(const Case& c)
{
  try
  {
    return static_cast<double>(c.time_integration.number_of_steps(c.end_time())) *
           c.discretisation.n_intervals;
  }
  catch (const std::exception&)
  {
    return 0.;
  }
}

/// The number of pantographs of @p c that can be in contact (rows per run).
unsigned int pantographs_of(const Case& c)
{
  unsigned int n = 0;
  for (const PantographCase& p : c.scene.pantographs)
    n += p.has_body() ? 1 : 0;
  return n;
}

/**
 * The dropper lengths of @p base as the runs install them before the
 * deviations: designed (form-finding, as the CaseRunner does it) or given.
 */
std::vector<double> dropper_lengths_before_deviations(const Case& base)
{
  if (!needs_design(base.scene, base.catenary))
    return base.catenary.dropper_lengths;
  const auto space = create_catenary_discretisation(base.catenary, base.discretisation);
  return design_catenary(base.scene, base.catenary, *space).catenary.dropper_lengths;
}

/**
 * Refuses a Monte Carlo dropper length tolerance that reaches the shortest
 * dropper of @p base: its samples would install droppers of length <= 0 (a
 * uniform draw reaches -tolerance, a normal one does so at 3 sigma).
 */
void check_dropper_tolerance(const Case& base, const SweepParameters& s)
{
  if (s.dropper_length_tolerance <= 0.)
    return;
  const std::vector<double> lengths = dropper_lengths_before_deviations(base);
  const auto shortest = std::min_element(lengths.begin(), lengths.end());
  if (shortest == lengths.end())
    return;
  const auto j = static_cast<std::size_t>(shortest - lengths.begin());
  require(s.dropper_length_tolerance < *shortest, "Sweep/Dropper length tolerance",
          s.dropper_length_tolerance,
          "reaches the shortest dropper (dropper " + std::to_string(j + 1) +
              " at x = " + number_to_string(base.catenary.dropper_positions[j], 6) +
              " m, " + number_to_string(*shortest, 6) +
              " m long before the deviations): samples would install droppers of "
              "length <= 0, which Catenary/Droppers/Lengths refuses; allowed: a "
              "tolerance below " +
              number_to_string(*shortest, 6) + " m");
}

/// The parameters that decide a sweep's rows: every entry that sweep_reads().
ParameterFingerprint sweep_parameters_of(const dealii::ParameterHandler& prm)
{
  ParameterFingerprint all = resolved_parameters(prm);
  all.erase(std::remove_if(all.begin(), all.end(),
                           [](const auto& e) { return !sweep_reads(e.first); }),
            all.end());
  return all;
}

/// Fills the costs and row counts of @p plan from each run's case (0 if refused).
void estimate(SweepPlan& plan, const std::function<SweepCase(unsigned int)>& make_run,
              const Case& base)
{
  for (unsigned int k = 0; k < plan.size(); ++k)
  {
    double cost = 0.;
    unsigned int n = pantographs_of(base);
    try
    {
      const SweepCase run = make_run(k);
      cost = cost_of(run.case_data), n = pantographs_of(run.case_data);
    }
    catch (const InputError&) // refused when it runs: a row with the reason
    {
    }
    plan.costs.push_back(cost);
    plan.pantographs.push_back(n);
  }
}
} // namespace

void check_swept_entries(const dealii::ParameterHandler& prm, const SweepParameters& s)
{
  const boost::property_tree::ptree tree = parameter_tree(prm);
  const char* which[] = {"Parameter", "Second parameter"};
  const char* values[] = {"Values", "Second values"};
  for (std::size_t e = 0; e < s.entries.size(); ++e)
    check_entry(tree, which[e], values[e], s.entries[e], s.values_text[e], s.values[e]);
  for (const std::string& entry : s.entries)
    require(entry.rfind("Sweep/", 0) != 0, "Sweep/Parameter", entry,
            "the sweep's own entries cannot be swept");
}

void run_sweep(const ProgramParameters& p, const dealii::ParameterHandler& prm,
               const SweepInput& input, std::ostream& out)
{
  const SweepParameters& s = p.sweep;
  SweepPlan plan;
  std::function<SweepCase(unsigned int)> make_run;
  const Case base = p.make_case();
  if (p.mode == RunMode::speed_sweep)
  {
    plan.kind = SweepKind::speed;
    plan.key_columns = {"speed_kmh"};
    for (const double v : s.speeds_kmh)
      plan.keys.push_back({number_to_string(v, 12)});
    make_run = [&p, &input, speeds = s.speeds_kmh](const unsigned int k)
    { return read_run(input, speed_settings(p, speeds[k])); };
  }
  else if (p.mode == RunMode::parameter_sweep)
  {
    check_swept_entries(prm, s);
    plan.kind = SweepKind::parameter;
    plan.key_columns = s.entries;
    for (const std::string& a : s.values[0])
      for (const std::string& b :
           s.values.size() > 1 ? s.values[1] : std::vector<std::string>{""})
        plan.keys.push_back(s.values.size() > 1 ? std::vector<std::string>{a, b}
                                                : std::vector<std::string>{a});
    make_run = [&input, &s, keys = plan.keys](const unsigned int k)
    {
      std::vector<std::string> settings;
      for (std::size_t e = 0; e < s.entries.size(); ++e)
        settings.push_back(s.entries[e] + "=" + keys[k][e]);
      return read_run(input, settings);
    };
  }
  else
  {
    check_dropper_tolerance(base, s);
    plan.kind = SweepKind::monte_carlo;
    plan.key_columns = {"sample"};
    for (unsigned int i = 0; i < s.samples; ++i)
      plan.keys.push_back({std::to_string(i)});
    const unsigned int n_droppers = base.catenary.n_droppers();
    const unsigned int n_arms = SteadyArms::positions(base.scene, base.catenary).size();
    make_run = [&p, &s, base, n_droppers, n_arms](const unsigned int k)
    {
      SweepCase run{base, p.statistics};
      run.case_data.installation = sample_deviations(s, n_droppers, n_arms, k);
      return run;
    };
  }
  estimate(plan, make_run, base);
  plan.parameters = sweep_parameters_of(prm);
  SweepStudy study(plan, make_run, s,
                   {p.output.directory, p.output.plots,
                    p.catenary.contact_wire.wave_speed(), p.output.report, p.assessment,
                    p.pantograph().speed, p.statistics.low_pass_cutoff,
                    plan.kind == SweepKind::parameter ? unit_of(prm, s.entries[0]) : ""});
  study.run(out);
}
} // namespace pantocat
