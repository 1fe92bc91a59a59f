#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>
#include <pantocat/io/output_parameters.h>

#include <deal.II/base/utilities.h>

namespace pantocat
{
void OutputParameters::declare_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Output");
  prm.declare_entry("Output directory", "output", dealii::Patterns::FileName(),
                    "Directory for all results; created if needed. The resolved "
                    "parameters are written to parameters.prm inside it.");
  prm.declare_entry("VTU subdivisions", "4", dealii::Patterns::Integer(1, 64),
                    "Sample points per cell in VTU files (shows the cubic Hermite "
                    "shape between vertices); the frames of an FDM run use its nodes.");
  prm.declare_entry("Time series interval", "1", dealii::Patterns::Integer(1),
                    "Write every k-th time step to time_series.csv.");
  prm.declare_entry("Plots", "true", dealii::Patterns::Bool(),
                    "Write PNG plots of the time series (needs gnuplot).");
  prm.declare_entry("Report", "true", dealii::Patterns::Bool(),
                    "Write report.html: the case, the window statistics, the assessment, "
                    "the plots (inline SVG, with Plots and gnuplot) and the events; one "
                    "self-contained page for any browser.");
  prm.declare_entry("VTU interval", "0", dealii::Patterns::Double(0.),
                    "Simulated time [s] between the ParaView frames of a dynamic run "
                    "(solution.pvd and vtu/*.vtu: both wires, pantograph and dropper "
                    "clamps); 0: no frames.");
  prm.declare_entry("Probe positions", "",
                    dealii::Patterns::List(dealii::Patterns::Double()),
                    "Positions x [m] on the contact wire whose displacement w_w(x) goes "
                    "into time_series.csv (columns w_w(x)); empty: none.");
  prm.declare_entry("Energy", "false", dealii::Patterns::Bool(),
                    "Write the energy v^T M v / 2 + q^T K q / 2 - f(t)^T q of the "
                    "semi-discrete system to time_series.csv and its range to "
                    "summary.json (costs one product with M and K per time point).");
  prm.declare_entry("Verbosity", "normal",
                    dealii::Patterns::Selection("quiet|normal|detailed"),
                    "quiet: print only errors; normal: the summary, the contact-force "
                    "statistics and the timer table, and a progress line on stderr when "
                    "it is a terminal and the run lasts over a second; detailed: also "
                    "the integrator's counters and every file written.");
  prm.leave_subsection();
}

void OutputParameters::parse_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Output");
  directory = prm.get("Output directory");
  require(!directory.empty(), "Output/Output directory", "''",
          "must name a directory (-o DIR or the entry)");
  vtu_subdivisions = prm.get_integer("VTU subdivisions");
  time_series_interval = prm.get_integer("Time series interval");
  plots = prm.get_bool("Plots");
  report = prm.get_bool("Report");
  vtu_interval = prm.get_double("VTU interval");
  probe_positions = dealii::Utilities::string_to_double(
      dealii::Utilities::split_string_list(prm.get("Probe positions")));
  energy = prm.get_bool("Energy");
  const std::string v = prm.get("Verbosity");
  verbosity = v == "quiet"      ? Verbosity::quiet
              : v == "detailed" ? Verbosity::detailed
                                : Verbosity::normal;
  prm.leave_subsection();
}

void OutputParameters::check(const double time_step, const double length) const
{
  // In every mode, also where no run measures them (studies, sweeps).
  for (const double x : probe_positions)
    require(x > 0. && x < length, "Output/Probe positions", x,
            "must lie inside (0, " + number_to_string(length) + ") m, the wires' domain");
  require(vtu_interval == 0. || vtu_interval >= time_step, "Output/VTU interval",
          vtu_interval,
          "must be 0 (no frames) or at least Time integration/Time step = " +
              number_to_string(time_step) + " s (a frame every time step)");
}
} // namespace pantocat
