#include <pantocat/app/run_modes.h>
#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>
#include <pantocat/base/safe_files.h>
#include <pantocat/io/elasticity_output.h>
#include <pantocat/io/json_writer.h>
#include <pantocat/io/wire_output.h>
#include <pantocat/simulation/case_runner.h>

#include <iomanip>
#include <optional>
#include <sstream>

namespace pantocat
{
namespace
{
/// Up to this many droppers, the screen lists the static force of each.
constexpr std::size_t max_droppers_listed = 10;

/// "90 droppers: static forces 70.19 N (dropper 1, x = 5 m) to 86.14 N (...), 0 slack".
void print_dropper_force_range(std::ostream& out, const std::vector<double>& positions,
                               const std::vector<unsigned int>& droppers,
                               const StaticEquilibrium& s)
{
  std::size_t low = 0, high = 0, slack = 0;
  for (std::size_t j = 0; j < droppers.size(); ++j)
  {
    const double f = s.multipliers[droppers[j]];
    low = f < s.multipliers[droppers[low]] ? j : low;
    high = f > s.multipliers[droppers[high]] ? j : high;
    slack += !s.active[droppers[j]];
  }
  out << std::setprecision(5) << "  " << droppers.size() << " droppers: static forces "
      << s.multipliers[droppers[low]] << " N (dropper " << low + 1
      << ", x = " << positions[low] << " m) to " << s.multipliers[droppers[high]]
      << " N (dropper " << high + 1 << ", x = " << positions[high] << " m), " << slack
      << " slack (each in dropper_forces.csv)\n";
}

/**
 * summary.json of the static mode: the problem, w_w under each pantograph, the
 * droppers, and the static check if there is one.
 */
void write_static_summary(const std::string& file, const ProgramParameters& p,
                          const CaseRunner& runner, const StaticEquilibrium& s,
                          const std::optional<StaticElasticity>& elasticity)
{
  std::ostringstream text;
  JsonWriter json(text);
  json.begin_object()
      .value("status", "completed")
      .value("mode", "static")
      .value("discretisation", to_string(p.discretisation.method))
      .value("number_of_intervals",
             static_cast<unsigned long>(p.discretisation.n_intervals))
      .value("unknowns", static_cast<unsigned long>(s.q.size()));
  json.begin_array("pantographs");
  for (const PantographCase& pantograph : p.scene.pantographs)
  {
    const double x = pantograph.parameters.initial_position;
    json.begin_object()
        .value("position", x)
        .value("contact_wire_displacement", runner.contact_wire_displacement(s.q, x))
        .end_object();
  }
  json.end_array();
  json.begin_array("droppers");
  const auto& droppers = runner.layout().dropper_indices;
  for (unsigned int j = 0; j < droppers.size(); ++j)
    json.begin_object()
        .value("x", p.catenary.dropper_positions[j])
        .value("force", s.multipliers[droppers[j]])
        .value("active", static_cast<bool>(s.active[droppers[j]]))
        .end_object();
  json.end_array();
  if (elasticity)
    write_elasticity_summary(json, *elasticity);
  json.end_object();
  write_file_atomically(file, text.str());
}
/// dropper_lengths.csv: span, dropper (in its span), x, the designed length and
/// the contact wire's target height there.
void write_dropper_lengths(const std::string& file, const CatenaryParameters& c)
{
  std::ostringstream csv;
  csv << "span,dropper,x,length,target_height\n" << std::setprecision(12);
  const std::vector<double> z = c.dropper_target_heights();
  unsigned int in_span = 0;
  for (unsigned int j = 0; j < c.n_droppers(); ++j)
  {
    in_span = j > 0 && c.dropper_spans[j] == c.dropper_spans[j - 1] ? in_span + 1 : 1;
    csv << c.dropper_spans[j] + 1 << ',' << in_span << ',' << c.dropper_positions[j]
        << ',' << c.dropper_lengths[j] << ',' << z[j] << '\n';
  }
  write_file_atomically(file, csv.str());
}

/// The design's targets in words: the Target heights, or the pre-sag and its reference.
std::string design_targets(const CatenaryParameters& c)
{
  if (!c.target_heights.empty())
    return "the target heights given";
  return "a pre-sag of " + number_to_string(c.presag) + " m (zero at the " +
         (c.presag_reference == PresagReference::supports ? "supports"
                                                          : "first and last dropper") +
         ")";
}

/// dropper_lengths.csv of a designed catenary @p c and a line on screen.
void write_design(const CatenaryParameters& c, const unsigned int iterations,
                  const std::string& dir, std::ostream& out,
                  std::vector<std::string>& written)
{
  write_dropper_lengths(dir + "/dropper_lengths.csv", c);
  written.push_back("dropper_lengths.csv");
  out << "  dropper lengths designed for " << design_targets(c) << " in " << iterations
      << " iterations (dropper_lengths.csv)\n";
}

/// The droppers' positions of span @p span (1-based) of @p c.
std::vector<double> droppers_of_span(const CatenaryParameters& c, const unsigned int span)
{
  std::vector<double> x;
  for (unsigned int j = 0; j < c.n_droppers(); ++j)
    if (c.dropper_spans[j] + 1 == span)
      x.push_back(c.dropper_positions[j]);
  return x;
}

/**
 * elasticity.csv, elasticity.png (if plots are asked for) and the figures of
 * each force on screen; adds the names of the files written to @p written.
 */
void write_elasticity(const ProgramParameters& p, const StaticElasticity& e,
                      std::ostream& out, std::vector<std::string>& written)
{
  const std::string& dir = p.output.directory;
  write_elasticity_csv(dir + "/elasticity.csv", e);
  written.push_back("elasticity.csv");
  if (p.output.plots)
  {
    const std::string title = std::string(to_string(p.discretisation.method)) +
                              ", N+1 = " + std::to_string(p.discretisation.n_intervals);
    if (plot_elasticity(dir, e, droppers_of_span(p.catenary, e.span), title))
      written.push_back("elasticity.png");
    written.push_back("elasticity.gp");
  }
  out << "  static elasticity of span " << e.span << " (" << e.x.size()
      << " points from x = " << e.x.front() << " to " << e.x.back()
      << " m; the catenary alone, droppers free to slacken): " << e.solves << " solves, "
      << e.active_set_iterations << " active-set iterations, " << std::setprecision(3)
      << e.seconds << " s\n";
  for (unsigned int f = 0; f < e.forces.size(); ++f)
  {
    const ElasticityFigures g = e.figures(f);
    unsigned int slack_points = 0;
    for (const auto& slack : e.slackened[f])
      slack_points += slack.empty() ? 0 : 1;
    out << "    F = " << g.force << " N: e_min = " << std::setprecision(4) << g.minimum
        << ", e_max = " << g.maximum << ", mean = " << g.mean
        << " mm/N, uniformity (e_max - e_min)/(e_max + e_min) = " << g.uniformity
        << "; droppers slacken at " << slack_points << " of " << e.x.size()
        << " points\n";
  }
}
} // namespace

void run_static_equilibrium(const ProgramParameters& p, std::ostream& out,
                            RunPhase& phase)
{
  require(p.scene.contact_wire == WireModel::elastic, "Scene/Contact wire", "rigid",
          "Mode = static computes the elastic catenary at rest: allowed elastic");
  // The catenary of the case with the pantographs' initial contact forces (or
  // moving forces) at their initial positions, (25) and (33).
  const CaseRunner runner(p.make_case());
  phase.begin("static solve"); // clears the results of an earlier run
  const StaticEquilibrium s = runner.static_catenary();
  std::optional<StaticElasticity> elasticity;
  if (p.elasticity.enabled())
    elasticity = runner.static_elasticity(p.elasticity);
  phase.begin("output");
  const SemiDiscreteSystem& system = runner.system();

  const std::string& dir = p.output.directory;
  write_wire_profiles(runner.discretisation(), system, s.q, dir + "/static_profile.csv",
                      dir + "/static_profile.vtu", p.output.vtu_subdivisions);
  std::ostringstream csv;
  csv << "dropper,x_m,force_n,gap_m,active\n" << std::setprecision(12);
  const auto& droppers = runner.layout().dropper_indices;
  out << "Static equilibrium (" << to_string(p.discretisation.method)
      << ", N+1 = " << p.discretisation.n_intervals << ", " << s.q.size() << " unknowns, "
      << droppers.size() << " dropper constraints)\n";
  for (unsigned int k = 0; k < p.scene.pantographs.size(); ++k)
  {
    const PantographCase& pantograph = p.scene.pantographs[k];
    const double force = pantograph.has_body()
                             ? runner.layout().pantographs[k].initial_contact_force
                         : pantograph.is_moving_force() ? pantograph.moving_force
                                                        : 0.;
    const double x = pantograph.parameters.initial_position;
    out << "  contact load " << force << " N at x_p = " << x
        << " m; contact wire there: " << std::setprecision(6)
        << runner.contact_wire_displacement(s.q, x) << " m\n";
  }
  // A section's droppers in one line (all of them in dropper_forces.csv).
  const bool list_droppers =
      droppers.size() <= max_droppers_listed || p.output.verbosity == Verbosity::detailed;
  for (unsigned int j = 0; j < droppers.size(); ++j)
  {
    const unsigned int i = droppers[j];
    csv << j + 1 << ',' << p.catenary.dropper_positions[j] << ',' << s.multipliers[i]
        << ',' << s.gaps[i] << ',' << (s.active[i] ? 1 : 0) << '\n';
    if (list_droppers)
      out << "  " << runner.layout().constraint_names[i]
          << " at x = " << p.catenary.dropper_positions[j] << " m: force "
          << std::setprecision(6) << s.multipliers[i] << " N"
          << (s.active[i] ? "" : " (slack)") << '\n';
  }
  if (!list_droppers)
    print_dropper_force_range(out, p.catenary.dropper_positions, droppers, s);
  write_file_atomically(dir + "/dropper_forces.csv", csv.str());
  std::vector<std::string> written{"static_profile.csv", "static_profile.vtu",
                                   "dropper_forces.csv"};
  if (!p.catenary.stitch_wires.empty())
  {
    write_stitch_wire_profiles(runner.discretisation(), system, s.q,
                               dir + "/stitch_wires.csv");
    written.push_back("stitch_wires.csv");
  }
  if (runner.design() && p.catenary.design == DropperDesign::designed)
    write_design(runner.case_data().catenary, runner.design()->iterations, dir, out,
                 written);
  if (elasticity)
    write_elasticity(p, *elasticity, out, written);
  write_static_summary(dir + "/summary.json", p, runner, s, elasticity);
  written.push_back("summary.json");
  out << "  wrote ";
  for (unsigned int i = 0; i < written.size(); ++i)
    out << (i > 0 ? ", " : "") << written[i];
  out << " to " << dir << '\n';
}
} // namespace pantocat
