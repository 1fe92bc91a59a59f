#include <pantocat/app/run_modes.h>
#include <pantocat/base/input_error.h>
#include <pantocat/io/wire_output.h>
#include <pantocat/simulation/case_runner.h>

#include <fstream>
#include <iomanip>

namespace pantocat
{
void run_static_equilibrium(const ProgramParameters& p, std::ostream& out)
{
  require(p.scene.contact_wire == WireModel::elastic, "Scene/Contact wire", "rigid",
          "Mode = static computes the elastic catenary at rest: allowed elastic");
  // The catenary of the case with the pantographs' initial contact forces (or
  // moving forces) at their initial positions, (25) and (33).
  const CaseRunner runner(p.make_case());
  const StaticEquilibrium s = runner.static_catenary();
  const SemiDiscreteSystem& system = runner.system();

  const std::string& dir = p.output.directory;
  write_wire_profiles(runner.discretisation(), system, s.q, dir + "/static_profile.csv",
                      dir + "/static_profile.vtu", p.output.vtu_subdivisions);
  std::ofstream csv(dir + "/dropper_forces.csv");
  csv << "dropper,x_m,force_n,gap_m,active\n" << std::setprecision(12);
  const auto& droppers = runner.layout().dropper_indices;
  out << "Static equilibrium (" << to_string(p.discretisation.method)
      << ", N+1 = " << p.discretisation.n_intervals << ", " << s.q.size() << " unknowns, "
      << droppers.size() << " dropper constraints)\n";
  for (const PantographCase& pantograph : p.scene.pantographs)
  {
    const double force = pantograph.has_body()
                             ? pantograph.parameters.initial_contact_force
                         : pantograph.is_moving_force() ? pantograph.moving_force
                                                        : 0.;
    const double x = pantograph.parameters.initial_position;
    out << "  contact load " << force << " N at x_p = " << x
        << " m; contact wire there: " << std::setprecision(6)
        << runner.contact_wire_displacement(s.q, x) << " m\n";
  }
  for (unsigned int j = 0; j < droppers.size(); ++j)
  {
    const unsigned int i = droppers[j];
    csv << j + 1 << ',' << p.catenary.dropper_positions[j] << ',' << s.multipliers[i]
        << ',' << s.gaps[i] << ',' << (s.active[i] ? 1 : 0) << '\n';
    out << "  " << runner.layout().constraint_names[i]
        << " at x = " << p.catenary.dropper_positions[j] << " m: force "
        << std::setprecision(6) << s.multipliers[i] << " N"
        << (s.active[i] ? "" : " (slack)") << '\n';
  }
  if (!csv)
    throw SimulationError("cannot write " + dir + "/dropper_forces.csv");
  out << "  wrote static_profile.csv, static_profile.vtu, dropper_forces.csv to " << dir
      << '\n';
}
} // namespace pantocat
