#pragma once

#include <pantocat/time/time_integration_parameters.h>

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <utility>
#include <vector>

namespace pantocat
{
/// (name "Subsection/Entry", value) of every parameter a checkpoint depends on.
using ParameterFingerprint = std::vector<std::pair<std::string, std::string>>;

/// Subsection Checkpoint: saving a run every K steps and continuing it.
struct CheckpointParameters
{
  unsigned int interval = 0; ///< steps between checkpoints; 0: none
  bool resume = false;       ///< continue from the output directory's checkpoint
  /// Stop the run after this many steps as if it were killed (0: never); for tests.
  unsigned long stop_after_steps = 0;

  static void declare_parameters(dealii::ParameterHandler& prm);
  void parse_parameters(dealii::ParameterHandler& prm);
  /// Refuses checkpoints for an integrator that cannot write them (IDA).
  void check(const std::string& integrator) const;
};
} // namespace pantocat
