#pragma once

#include <pantocat/app/program_parameters.h>
#include <pantocat/app/run_phase.h>

#include <ostream>

namespace pantocat
{
/// Table 1: extreme eigenfrequencies of both wires; writes eigenfrequencies.csv.
void run_eigenfrequencies(const ProgramParameters& parameters, std::ostream& out,
                          RunPhase& phase);

/**
 * The initial static catenary (Sec. 2.2, Fig. 5): gravity, clamp loads,
 * dropper constraints and the contact load lambda_p(0) at x_p(0). Writes
 * static_profile.csv/.vtu and dropper_forces.csv.
 */
void run_static_equilibrium(const ProgramParameters& parameters, std::ostream& out,
                            RunPhase& phase);

/**
 * The coupled run of Sec. 6: writes time_series.csv (streamed), summary.json
 * and PNG plots of lambda_p, lambda_d and w_p (Figs. 6, 7), and prints a
 * short summary. Enters the phases "time loop" and "output" of @p phase.
 */
void run_dynamics(const ProgramParameters& parameters, std::ostream& out,
                  RunPhase& phase);

} // namespace pantocat
