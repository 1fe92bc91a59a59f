#include <pantocat/analysis/eigenfrequency_analysis.h>
#include <pantocat/analysis/stability_limit.h>
#include <pantocat/app/run_modes.h>
#include <pantocat/base/input_error.h>
#include <pantocat/base/safe_files.h>
#include <pantocat/io/json_writer.h>

#include <iomanip>
#include <sstream>

namespace pantocat
{
void run_eigenfrequencies(const ProgramParameters& p, std::ostream& out, RunPhase& phase)
{
  phase.begin("eigenvalues"); // clears the results of an earlier run
  std::vector<SubsystemFrequencies> rows;
  out << "Eigenfrequencies of the undamped wires, N+1 = " << p.discretisation.n_intervals
      << " (Table 1)\n"
      << std::left << std::setw(6) << "disc." << std::setw(14) << "subsystem"
      << std::right << std::setw(13) << "f_min [Hz]" << std::setw(13) << "f_max [Hz]"
      << std::setw(14) << "2/omega_max"
      << "    paper (N+1 = 500): f_min, f_max\n";
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
          << std::setprecision(5) << "    "
          << PaperTable1::f_min(f.discretisation, f.subsystem) << ", "
          << PaperTable1::f_max(f.discretisation, f.subsystem) << '\n';
      rows.push_back(f);
    }
    out << "  step-size limit of the half-explicit method, 2/omega_max ("
        << to_string(method) << "): " << std::setprecision(3)
        << explicit_step_size_limit(frequencies)
        << " s  (paper: " << (method == SpaceMethod::fdm ? "6.6e-05" : "5.3e-06")
        << " s)\n";
  }
  phase.begin("output");
  std::ostringstream csv;
  csv << "discretisation,subsystem,f_min_hz,f_max_hz\n" << std::setprecision(10);
  std::ostringstream summary;
  JsonWriter json(summary);
  json.begin_object().value("status", "completed").value("mode", "eigenfrequencies");
  json.begin_array("subsystems");
  for (const auto& f : rows)
  {
    csv << f.discretisation << ',' << f.subsystem << ',' << f.f_min_hz << ','
        << f.f_max_hz << '\n';
    json.begin_object()
        .value("discretisation", f.discretisation)
        .value("subsystem", f.subsystem)
        .value("f_min_hz", f.f_min_hz)
        .value("f_max_hz", f.f_max_hz)
        .end_object();
  }
  json.end_array();
  json.end_object();
  write_file_atomically(p.output.directory + "/eigenfrequencies.csv", csv.str());
  write_file_atomically(p.output.directory + "/summary.json", summary.str());
}
} // namespace pantocat
