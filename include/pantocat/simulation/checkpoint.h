#pragma once

#include <pantocat/base/checkpoint_archive.h>
#include <pantocat/base/input_error.h>
#include <pantocat/simulation/checkpoint_parameters.h>
#include <pantocat/simulation/time_point.h>
#include <pantocat/time/time_integrator.h>

#include <deal.II/base/parameter_handler.h>

#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace pantocat
{
/// Every entry of @p prm ("Subsection/Entry", value as written), in the order printed.
ParameterFingerprint resolved_parameters(const dealii::ParameterHandler& prm);

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
 * Writes checkpoints of a dynamic run: the fingerprint of its parameters, the
 * step counter, the integrator's internal state and each observer's state,
 * in a Boost binary archive (the payload). The file holds a header line, the
 * payload's length and its CRC-32, then the payload. It is written as a whole by
 * write_file_atomically() (a temporary file of a random name in the same
 * directory, renamed over the old checkpoint): a run killed while writing
 * leaves the previous checkpoint intact, and no link at the checkpoint's
 * name is followed.
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
 * Reads a checkpoint. The constructor refuses a file that is no regular file
 * (a link, a FIFO, a device: read_regular_file(), without reading it) or
 * holds more than 4 GiB, reads the whole file and checks,
 * before deserialising anything, its header, the payload's length and its
 * CRC-32 (any flipped bit or byte, a file cut short or extended is refused);
 * then that it was made with @p fingerprint (an InputError names the first
 * parameter that differs, with both values) and that its step lies inside
 * the run. restore() then loads the integrator (made and initialised for the
 * same system) and the observers, in the order written, and checks what it
 * read: the state's sizes against the system, finite values, the step
 * counters and the time of that step, and that nothing is left over. Every
 * refusal is an InputError naming the file and what is wrong; restore()
 * refuses before any output file is changed (TimeSeriesWriter cuts its file
 * only when the run goes on).
 */
class CheckpointReader
{
public:
  /**
   * Reads @p file for a run of @p run_steps steps of @p time_step seconds
   * (CaseRunner::number_of_steps(), CaseRunner::time_step()).
   */
  CheckpointReader(const std::string& file, const ParameterFingerprint& fingerprint,
                   unsigned long run_steps, double time_step);
  ~CheckpointReader();
  /// The number of steps done when the checkpoint was written.
  unsigned long step() const { return steps; }
  void restore(TimeIntegrator& integrator, const SimulationLayout& layout,
               const std::vector<SimulationObserver*>& observers);

private:
  /// "Checkpoint/Resume from checkpoint = true: ", which starts each refusal.
  static std::string refusal();
  /// The refusal of a damaged checkpoint, saying @p what is wrong.
  InputError damaged(const std::string& what) const;
  /// The payload of the file's @p bytes, after the header, length and checksum checks.
  std::string verified_payload(const std::string& bytes) const;
  void check_fingerprint(const ParameterFingerprint& saved,
                         const ParameterFingerprint& fingerprint) const;
  /// The loaded integrator's step counter and time against the header's step.
  void check_integrator(const TimeIntegrator& integrator, double t0) const;

  std::string file_name;
  std::istringstream payload;
  std::unique_ptr<CheckpointIn> archive;
  unsigned long steps = 0;
  double time_step = 0.; ///< the step the run takes
};
} // namespace pantocat
