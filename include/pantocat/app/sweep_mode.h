#pragma once

#include <pantocat/app/program_parameters.h>

#include <deal.II/base/parameter_handler.h>

#include <ostream>
#include <string>
#include <vector>

namespace pantocat
{
/// Where the parameters of a sweep came from: each run re-reads them with its own
/// settings.
struct SweepInput
{
  std::string file;                   ///< the parameter file
  std::vector<std::string> overrides; ///< the command line's --set (and -o) settings
};

/**
 * Checks the entries and values of Mode = parameter sweep against the
 * declared parameters in @p prm: each entry must exist, be one the runs of a
 * sweep read (not of subsection Output, Checkpoint, Study, Eigenfrequencies,
 * Elasticity or Sweep) and be numeric (pattern Double or Integer), each
 * value must match its pattern. Throws
 * InputError naming Sweep/Parameter (or Values, Second ...), the value and
 * what is allowed.
 */
void check_swept_entries(const dealii::ParameterHandler& prm,
                         const SweepParameters& sweep);

/**
 * Mode = speed sweep | parameter sweep | monte carlo (every rank calls it):
 * the plan of runs from subsection Sweep, each run's case made by reading
 * @p input again with the run's settings (a speed, the entries' values) or,
 * for Monte Carlo, the base case with the sample's installation deviations
 * (a dropper length tolerance that reaches the shortest dropper is refused);
 * run by SweepStudy over the MPI ranks. The plan carries the parameters that
 * decide the rows (all but those check_swept_entries() refuses to sweep),
 * which a resumed sweep's partial file must match.
 */
void run_sweep(const ProgramParameters& parameters, const dealii::ParameterHandler& prm,
               const SweepInput& input, std::ostream& out);
} // namespace pantocat
