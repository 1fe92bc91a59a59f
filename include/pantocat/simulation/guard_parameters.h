#pragma once

#include <deal.II/base/parameter_handler.h>

namespace pantocat
{
/**
 * Subsection Guards: the bounds beyond which a dynamic run counts as unstable
 * and stops (doc/stability.md gives the reasoning and measured
 * figures).
 */
struct GuardParameters
{
  /// Largest |g_i(t, q)| of an active constraint [m].
  double drift_tolerance = 1e-6;
  /// Largest |lambda_i| as a multiple of the reference force F_ref.
  double multiplier_bound = 100.;
  /// Largest E(t) - E(0) as a multiple of the reference energy E_ref.
  double energy_bound = 0.01;

  static void declare_parameters(dealii::ParameterHandler& prm);
  void parse_parameters(dealii::ParameterHandler& prm);
};

} // namespace pantocat
