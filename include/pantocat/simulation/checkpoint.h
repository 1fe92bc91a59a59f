#pragma once

#include <pantocat/base/checkpoint_archive.h>
#include <pantocat/simulation/checkpoint_parameters.h>
#include <pantocat/simulation/time_point.h>
#include <pantocat/time/time_integrator.h>

#include <deal.II/base/parameter_handler.h>

#include <fstream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace pantocat
{
/**
 * The parameters that decide what a dynamic run computes and writes: every
 * entry of @p prm except subsection Checkpoint, Run/Mode-independent ones of
 * other modes (Study, Eigenfrequencies), Output/Output directory,
 * Output/Verbosity, Output/Plots and Time integration/Force step size. A
 * checkpoint is only continued with the same values (grid, discretisation,
 * integrator, time step, catenary, pantograph, scene, outputs, ...).
 */
ParameterFingerprint critical_parameters(const dealii::ParameterHandler& prm);

/**
 * Writes checkpoints of a dynamic run: the fingerprint of its
 * parameters, the step counter, the integrator's internal state and each
 * observer's state, in a Boost binary archive. Written to a temporary file
 * in the same directory and renamed over the old checkpoint: a run killed
 * while writing leaves the previous checkpoint intact.
 */
class CheckpointWriter
{
public:
  CheckpointWriter(std::string file, ParameterFingerprint fingerprint);
  void write(unsigned long step, const TimeIntegrator& integrator,
             const std::vector<SimulationObserver*>& observers) const;
  const std::string& file() const { return file_name; }

private:
  std::string file_name;
  ParameterFingerprint fingerprint;
};

/**
 * Reads a checkpoint: the constructor checks that it is one and that it was
 * made with @p fingerprint (an InputError names the first parameter that
 * differs, with both values); restore() then loads the integrator (made and
 * initialised for the same system) and the observers, in the order written.
 */
class CheckpointReader
{
public:
  CheckpointReader(const std::string& file, const ParameterFingerprint& fingerprint);
  ~CheckpointReader();
  /// The number of steps done when the checkpoint was written.
  unsigned long step() const { return steps; }
  void restore(TimeIntegrator& integrator, const SimulationLayout& layout,
               const std::vector<SimulationObserver*>& observers);

private:
  std::string file_name;
  std::ifstream in;
  std::unique_ptr<CheckpointIn> archive;
  unsigned long steps = 0;
};
} // namespace pantocat
