#include <pantocat/base/input_error.h>
#include <pantocat/simulation/guard_parameters.h>

namespace pantocat
{
void GuardParameters::declare_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Guards");
  prm.declare_entry("Constraint drift tolerance", "1e-6", dealii::Patterns::Double(0.),
                    "Stop a dynamic run when an active constraint's position residual "
                    "|g_i| exceeds this [m] (the projected methods keep it at round-off, "
                    "IDA near its tolerance, about 1e-9 m).");
  prm.declare_entry("Multiplier bound", "100", dealii::Patterns::Double(0.),
                    "Stop when a constraint force |lambda_i| exceeds this multiple of "
                    "F_ref = max(static force F_0, initial constraint forces).");
  prm.declare_entry("Energy bound", "0.01", dealii::Patterns::Double(0.),
                    "Stop when the energy E(t) - E(0) of the semi-discrete system "
                    "exceeds this multiple of (T_c + T_w) L / 2, the strain energy of "
                    "both wires at an RMS slope of 1 (0.01: an RMS slope of 0.1).");
  prm.leave_subsection();
}

void GuardParameters::parse_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Guards");
  drift_tolerance = prm.get_double("Constraint drift tolerance");
  multiplier_bound = prm.get_double("Multiplier bound");
  energy_bound = prm.get_double("Energy bound");
  prm.leave_subsection();
  require(drift_tolerance > 0., "Guards/Constraint drift tolerance", drift_tolerance,
          "must be > 0");
  require(multiplier_bound > 0., "Guards/Multiplier bound", multiplier_bound,
          "must be > 0");
  require(energy_bound > 0., "Guards/Energy bound", energy_bound, "must be > 0");
}
} // namespace pantocat
