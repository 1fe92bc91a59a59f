#pragma once

#include <pantocat/space/catenary_discretisation.h>

#include <string>
#include <vector>

namespace pantocat
{
/// Lowest and highest eigenfrequency of one undamped wire (one row of Table 1).
struct SubsystemFrequencies
{
  std::string discretisation; ///< "fem" | "fdm"
  std::string subsystem;      ///< "carrier" | "contact wire"
  double f_min_hz = 0.;
  double f_max_hz = 0.;
};

/**
 * Eigenfrequencies f = omega / (2 pi) of K x = omega^2 M x for each wire
 * alone, undamped and unconstrained (Table 1 of Sec. 6).
 */
std::vector<SubsystemFrequencies>
compute_extreme_frequencies(const CatenaryDiscretisation& discretisation);

/**
 * The step-size limit 2 / omega_max of the explicit (half-explicit) method
 * for the largest circular frequency omega_max over the given subsystems
 * (Sec. 6: 6.6e-5 s FDM, 5.3e-6 s FEM at N+1 = 500).
 */
double explicit_step_size_limit(const std::vector<SubsystemFrequencies>& frequencies);

/// Table 1 of the paper (Hz, N+1 = 500), for the comparison printed beside ours.
struct PaperTable1
{
  static double f_min(const std::string& discretisation, const std::string& subsystem);
  static double f_max(const std::string& discretisation, const std::string& subsystem);
};
} // namespace pantocat
