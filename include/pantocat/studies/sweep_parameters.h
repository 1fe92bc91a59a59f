#pragma once

#include <deal.II/base/parameter_handler.h>

#include <cstdint>
#include <string>
#include <vector>

namespace pantocat
{
/// How the installation deviations of a Monte Carlo study are distributed.
enum class DeviationDistribution
{
  uniform, ///< uniform in [-tolerance, +tolerance]
  normal   ///< normal with mean 0 and standard deviation tolerance / 3 (3 sigma =
           ///< tolerance)
};

/**
 * A list of values as a user writes it in a sweep: "200, 220, 250" or a
 * range "200 to 400 step 20" (first, last and the step, last included when
 * the step reaches it to 1e-9 of the step). Throws InputError naming
 * @p parameter for text that is neither, an empty range (last < first, a
 * step <= 0) or an empty list.
 */
std::vector<double> parse_sweep_values(const std::string& text,
                                       const std::string& parameter);

/**
 * The "Sweep" subsection: Mode = speed sweep (the speeds), parameter sweep
 * (one or two prm entries and their values; two make a grid), monte carlo
 * (samples of installation deviations). Every run is the base case with its
 * entries changed, run by the CaseRunner; the runs are spread over the MPI
 * ranks by a work queue on rank 0.
 */
struct SweepParameters
{
  std::vector<double> speeds_kmh; ///< Speeds [km/h] (speed sweep)
  std::string speeds_text;        ///< as written, for messages
  /// Parameter sweep: the entries ("Catenary/Contact wire/Tension"), one or two.
  std::vector<std::string> entries;
  /// Values of each entry, as written (one list per entry; a range expanded).
  std::vector<std::vector<std::string>> values;
  std::vector<std::string> values_text; ///< as written, per entry

  unsigned int samples = 0; ///< Monte Carlo: number of samples
  std::uint64_t seed = 1;   ///< sample i draws from mt19937_64(seed + i)
  DeviationDistribution distribution = DeviationDistribution::uniform;
  double dropper_length_tolerance = 0.;    ///< [m]
  double steady_arm_height_tolerance = 0.; ///< [m]
  double tension_tolerance = 0.;           ///< relative, of both wires' tensions

  bool resume = false; ///< skip the runs a killed sweep already finished
  /// Stop after this many runs as if killed (0: never); for tests.
  unsigned int stop_after_runs = 0;
  std::string
      output_name; ///< file base name; empty: speed_sweep | parameter_sweep | monte_carlo

  static void declare_parameters(dealii::ParameterHandler& prm);
  /// Reads the subsection; the lists of the chosen @p mode are checked here.
  void parse_parameters(dealii::ParameterHandler& prm, const std::string& mode);
};
} // namespace pantocat
