#pragma once

#include <pantocat/simulation/case.h>
#include <pantocat/simulation/contact_statistics.h>
#include <pantocat/simulation/statistics_parameters.h>
#include <pantocat/studies/sweep_parameters.h>

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace pantocat
{
/// One run of a sweep: the case with its entries changed, and how it is evaluated.
struct SweepCase
{
  Case case_data;
  StatisticsParameters statistics;
};

/// The evaluation of one pantograph in one run of a sweep.
struct PantographFigures
{
  unsigned int number = 1; ///< 1-based, as in "Pantograph k"
  ForceFigures raw;
  bool has_filtered = false;
  ForceFigures filtered; ///< after the low pass (has_filtered)
  bool has_uplift = false;
  double max_steady_arm_uplift = 0.; ///< [m] (has_uplift)
};

/// What one run of a sweep gives back (packable, sent from a rank to rank 0).
struct SweepOutcome
{
  enum class Status
  {
    completed,
    failed, ///< stopped by a guard or an instability (SimulationError)
    refused ///< the case of this run is not allowed (InputError)
  };
  Status status = Status::completed;
  std::string reason;       ///< why failed or refused (one line)
  double wall_seconds = 0.; ///< of this run, on its rank
  double cpu_seconds =
      0.; ///< CPU time of this run (less than wall_seconds when the core is shared)
  unsigned long steps = 0;                    ///< time steps integrated
  unsigned int rank = 0;                      ///< the MPI rank that ran it
  std::vector<PantographFigures> pantographs; ///< every pantograph in contact

  /// Bytes for MPI transfer; unpack() restores the same outcome exactly.
  std::vector<char> pack() const;
  static SweepOutcome unpack(const std::vector<char>& buffer);
};

const char* to_string(SweepOutcome::Status status);

/**
 * Runs @p run through the CaseRunner (its check() first) with one
 * ContactStatistics per pantograph in contact and returns their figures in
 * the evaluation window. A refusal (InputError) and a stopped run
 * (SimulationError) become an outcome with that status and the reason.
 * @p poll is called every few time steps (rank 0 serves the work queue
 * from it while it computes).
 */
SweepOutcome execute_sweep_run(const SweepCase& run, const std::function<void()>& poll);

/**
 * The installation deviations of Monte Carlo sample @p sample (0-based),
 * drawn from std::mt19937_64(seed + sample) in a fixed order (every dropper,
 * every steady arm, the carrier's and the contact wire's tension), whatever
 * tolerance is zero (a zero tolerance gives zero deviations), so that a
 * sample does not depend on the rank that runs it nor on the other tolerances.
 */
InstallationDeviations sample_deviations(const SweepParameters& parameters,
                                         unsigned int n_droppers,
                                         unsigned int n_steady_arms, unsigned int sample);
} // namespace pantocat
