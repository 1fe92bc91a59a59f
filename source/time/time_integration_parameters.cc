#include <pantocat/base/input_error.h>
#include <pantocat/base/physical_memory.h>
#include <pantocat/time/integrator_registry.h>
#include <pantocat/time/time_integration_parameters.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace pantocat
{
void TimeIntegrationParameters::declare_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Time integration");
  prm.declare_entry("Integrator", "half-explicit",
                    dealii::Patterns::Selection(integrator_selection()),
                    integrator_documentation());
  prm.declare_entry("Time step", "5e-5", dealii::Patterns::Double(0.),
                    "Constant step size dt [s], > 0 (Sec. 6: 5e-5 s).");
  prm.declare_entry("Force step size", "false", dealii::Patterns::Bool(),
                    "Run the half-explicit method even above its stability limit "
                    "2/omega_max (a warning instead of a refusal).");
  prm.declare_entry("Spectral radius at infinity", "0.5",
                    dealii::Patterns::Double(0., 1.),
                    "generalized-alpha: rho_inf in [0, 1], the damping of the highest "
                    "frequencies per step (1: none, the trapezoidal rule; 0: "
                    "asymptotic annihilation).");
  prm.declare_entry(
      "Linear solver", "banded",
      dealii::Patterns::Selection("banded|umfpack|trilinos-klu"),
      "Sparse direct solver of the implicit integrators (bdf2, generalized-alpha) "
      "for their constant iteration matrices and M: banded (banded Cholesky of "
      "LAPACK where the matrix is symmetric positive definite with a narrow "
      "band, else UMFPACK; the fastest, doc/benchmarks.md), umfpack (deal.II's "
      "SparseDirectUMFPACK), trilinos-klu (Trilinos Amesos KLU).");
  prm.declare_entry("IDA relative tolerance", "1e-6", dealii::Patterns::Double(0.),
                    "ida: relative tolerance of the local error (q, v).");
  prm.declare_entry("IDA absolute tolerance", "1e-8", dealii::Patterns::Double(0.),
                    "ida: absolute tolerance of the local error (q [m], v [m/s]).");
  prm.declare_entry("IDA maximum order", "2", dealii::Patterns::Integer(1, 5),
                    "ida: largest order of its BDF formulas, 1-5. Orders above 2 are not "
                    "A-stable: on the undamped wires of the paper they shrink the steps "
                    "to the periods of the highest frequencies (FEM at 32 m/s: 2 runs in "
                    "21 s, 5 in 227 s; doc/dynamics.md).");
  prm.declare_entry(
      "IDA linear solver", "sundials-klu",
      dealii::Patterns::Selection("sundials-klu|trilinos-klu|umfpack"),
      "ida: sparse direct solver of the Newton iterations on the Jacobian "
      "(not banded: the constraint rows couple distant unknowns): SUNDIALS' "
      "KLU (the fastest, doc/dynamics.md), Trilinos Amesos KLU, or UMFPACK.");
  prm.declare_entry("Maximum active-set iterations", "20", dealii::Patterns::Integer(1),
                    "Bound on the repetitions of one step while the active set of the "
                    "unilateral constraints changes (Sec. 5.3).");
  prm.leave_subsection();
}

void TimeIntegrationParameters::parse_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Time integration");
  integrator = prm.get("Integrator");
  ida_relative_tolerance = prm.get_double("IDA relative tolerance");
  ida_maximum_order = prm.get_integer("IDA maximum order");
  ida_absolute_tolerance = prm.get_double("IDA absolute tolerance");
  ida_linear_solver = prm.get("IDA linear solver");
  rho_infinity = prm.get_double("Spectral radius at infinity");
  const std::string solver = prm.get("Linear solver");
  linear_solver = solver == "umfpack"        ? LinearSolverType::umfpack
                  : solver == "trilinos-klu" ? LinearSolverType::trilinos_klu
                                             : LinearSolverType::banded;
  time_step = prm.get_double("Time step");
  force_step_size = prm.get_bool("Force step size");
  max_active_set_iterations = prm.get_integer("Maximum active-set iterations");
  prm.leave_subsection();
  require(time_step > 0., "Time integration/Time step", time_step, "must be > 0");
  require(ida_relative_tolerance > 0., "Time integration/IDA relative tolerance",
          ida_relative_tolerance, "must be > 0");
  require(ida_absolute_tolerance > 0., "Time integration/IDA absolute tolerance",
          ida_absolute_tolerance, "must be > 0");
}

void TimeIntegrationParameters::check_number_of_steps(const double end_time,
                                                      const std::string& run) const
{
  const double steps = steps_of(end_time);
  const double available = physical_memory_bytes();
  const double max_steps = available > 0. ? available / memory_per_step : 1e18;
  if (std::isfinite(steps) && steps <= max_steps)
    return;
  std::ostringstream allowed;
  allowed.precision(3);
  allowed << run << " would take " << steps << " steps; at " << memory_per_step
          << " bytes per step (the contact-force series) this machine allows at most "
          << max_steps << " steps";
  require(false, "Time integration/Time step", time_step, allowed.str());
}

double TimeIntegrationParameters::steps_of(const double end_time) const
{
  // 1e-9: a step that divides t_e up to rounding takes no extra step.
  return std::max(1., std::ceil(end_time / time_step - 1e-9));
}

unsigned long TimeIntegrationParameters::number_of_steps(const double end_time) const
{
  return static_cast<unsigned long>(steps_of(end_time));
}

double TimeIntegrationParameters::step_for(const double end_time) const
{
  const unsigned long n = number_of_steps(end_time);
  // Keep the requested step bit for bit when it divides t_e up to rounding.
  return std::abs(n * time_step - end_time) <= 1e-9 * time_step ? time_step
                                                                : end_time / n;
}
} // namespace pantocat
