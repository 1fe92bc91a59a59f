#include <pantocat/analysis/eigenfrequency_analysis.h>
#include <pantocat/analysis/static_equilibrium.h>
#include <pantocat/app/run_modes.h>
#include <pantocat/base/input_error.h>
#include <pantocat/io/wire_output.h>
#include <pantocat/system/catenary_system_builder.h>

#include <fstream>
#include <iomanip>

namespace pantocat
{
void run_eigenfrequencies(const ProgramParameters& p, std::ostream& out)
{
  std::vector<SubsystemFrequencies> rows;
  out << "Eigenfrequencies of the undamped wires, N+1 = " << p.discretisation.n_intervals
      << " (Table 1)\n"
      << std::left << std::setw(6) << "disc." << std::setw(14) << "subsystem"
      << std::right << std::setw(13) << "f_min [Hz]" << std::setw(13) << "f_max [Hz]"
      << std::setw(14) << "2/omega_max" << "    paper (N+1 = 500): f_min, f_max\n";
  for (const SpaceMethod method : p.eigenfrequency_discretisations)
  {
    DiscretisationParameters d = p.discretisation;
    d.method = method;
    const auto discretisation = create_catenary_discretisation(p.catenary, d);
    const auto frequencies = compute_extreme_frequencies(*discretisation);
    for (const auto& f : frequencies)
    {
      out << std::left << std::setw(6) << f.discretisation << std::setw(14) << f.subsystem
          << std::right << std::setprecision(5) << std::setw(13) << f.f_min_hz
          << std::setw(13) << f.f_max_hz << std::setw(14) << std::setprecision(2)
          << std::scientific << explicit_step_size_limit({f}) << std::defaultfloat
          << std::setprecision(5) << "    " << PaperTable1::f_min(f.discretisation, f.subsystem)
          << ", " << PaperTable1::f_max(f.discretisation, f.subsystem) << '\n';
      rows.push_back(f);
    }
    out << "  step-size limit of the half-explicit method, 2/omega_max ("
        << to_string(method) << "): " << std::setprecision(3)
        << explicit_step_size_limit(frequencies) << " s  (paper: "
        << (method == SpaceMethod::fdm ? "6.6e-05" : "5.3e-06") << " s)\n";
  }
  std::ofstream csv(p.output.directory + "/eigenfrequencies.csv");
  csv << "discretisation,subsystem,f_min_hz,f_max_hz\n" << std::setprecision(10);
  for (const auto& f : rows)
    csv << f.discretisation << ',' << f.subsystem << ',' << f.f_min_hz << ',' << f.f_max_hz
        << '\n';
  if (!csv)
    throw SimulationError("cannot write " + p.output.directory + "/eigenfrequencies.csv");
}

void run_static_equilibrium(const ProgramParameters& p, std::ostream& out)
{
  const auto d = create_catenary_discretisation(p.catenary, p.discretisation);
  const SemiDiscreteSystem system =
    build_catenary_system(*d, Constraint::Kind::unilateral);

  // The contact load lambda_p(0) F_w(0)^T at x_p(0), (25) and (33).
  dealii::Vector<double> contact_load(system.n_dofs());
  SparseRow F;
  d->load_row(p.pantograph.initial_position, 0, F);
  F.shift(system.block("contact wire").first);
  F.add_transpose_to(contact_load, p.pantograph.initial_contact_force);

  const StaticEquilibrium s = solve_static_equilibrium(system, contact_load);

  const std::string& dir = p.output.directory;
  write_wire_profiles(*d, system, s.q, dir + "/static_profile.csv",
                      dir + "/static_profile.vtu", p.output.vtu_subdivisions);
  std::ofstream csv(dir + "/dropper_forces.csv");
  csv << "dropper,x_m,force_n,gap_m,active\n" << std::setprecision(12);
  out << "Static equilibrium (" << to_string(d->method())
      << ", N+1 = " << d->n_intervals() << ", " << system.n_dofs() << " unknowns, "
      << system.n_constraints() << " dropper constraints)\n"
      << "  contact load " << p.pantograph.initial_contact_force << " N at x_p = "
      << p.pantograph.initial_position << " m; contact wire there: "
      << std::setprecision(6) << F.dot(s.q) << " m (delta_eps-weighted)\n";
  for (unsigned int j = 0; j < system.n_constraints(); ++j)
  {
    csv << j + 1 << ',' << p.catenary.dropper_positions[j] << ',' << s.multipliers[j]
        << ',' << s.gaps[j] << ',' << (s.active[j] ? 1 : 0) << '\n';
    out << "  " << system.constraints[j]->name() << " at x = "
        << p.catenary.dropper_positions[j] << " m: force " << std::setprecision(6)
        << s.multipliers[j] << " N" << (s.active[j] ? "" : " (slack)") << '\n';
  }
  if (!csv)
    throw SimulationError("cannot write " + dir + "/dropper_forces.csv");
  out << "  wrote static_profile.csv, static_profile.vtu, dropper_forces.csv to " << dir
      << '\n';
}
} // namespace pantocat
