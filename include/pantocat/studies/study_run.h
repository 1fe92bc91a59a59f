#pragma once

#include <pantocat/studies/contact_figures.h>
#include <pantocat/studies/study_case.h>

#include <optional>
#include <string>
#include <vector>

namespace pantocat
{
/// One run of a study: the case with its discretisation, N+1, integrator and dt replaced.
struct StudyRun
{
  SpaceMethod discretisation = SpaceMethod::fdm;
  std::string integrator = "half-explicit"; ///< a registered integrator
  unsigned int n_intervals = 500;           ///< N+1
  double time_step = 5e-5;                  ///< dt [s]
  bool reference = false;                   ///< the separate reference run
  /// unilateral | bilateral | penalty for every pantograph; empty: the case's law.
  std::string contact_law;
  Compliance penalty; ///< k_c, c_c of contact_law = penalty

  /// "fdm + half-explicit", "fdm + half-explicit, penalty contact" with a contact law.
  std::string method() const;
  /// "fdm + half-explicit, N+1 = 500, dt = 5e-05 s".
  std::string label() const;
  /// The contact law of pantograph 1 in @p base with this run's law applied.
  std::string contact_law_in(const Case& base) const;
  /// The case @p base with this run's discretisation, time integration and contact law.
  Case parameters(const Case& base) const;
};

/// What a study wants from each run besides lambda_p(t).
struct RunRequest
{
  /// Sample the contact wire at t_e at x_j = j L / wire_samples, j = 0..wire_samples
  /// (0: not at all).
  unsigned int wire_samples = 0;
  bool eigenfrequencies = false;
  /// Measure the ContactFigures in the window and with the low pass of these statistics.
  std::optional<StatisticsParameters> contact_statistics;
};

/// What a run of a study gives back (packable, to be gathered from MPI ranks).
struct RunOutcome
{
  enum class Status
  {
    completed,
    skipped, ///< half-explicit step above 2/omega_max: not run
    failed   ///< SimulationError during the run
  };
  Status status = Status::completed;
  std::string message;     ///< why skipped or failed
  double cpu_seconds = 0.; ///< set-up and time loop, CPU time of this process
  unsigned long steps = 0;
  std::vector<double> t, lambda_p; ///< every time point of the run
  std::vector<double> wire;        ///< w_w(x_j, t_e) at the requested samples [m]
  double f_min_carrier = 0., f_min_contact_wire = 0.; ///< [Hz]
  ContactFigures contact; ///< if RunRequest::contact_statistics

  /// Bytes for MPI transfer; unpack() restores the same outcome exactly.
  void pack(std::vector<char>& buffer) const;
  static RunOutcome unpack(const std::vector<char>& buffer, std::size_t& position);
};

const char* to_string(RunOutcome::Status status);

/**
 * Refuses, before any run starts, a study whose grids cannot carry the case
 * (e.g. N+1 too small for the droppers): an InputError that names the run and
 * says what is allowed. Each distinct discretisation and N+1 is built once.
 */
void check_study_grids(const std::vector<StudyRun>& runs, const Case& base);

/**
 * Runs @p run of the case @p base through the CaseRunner, skips a step above
 * the stability limit of an explicit integrator (the runner would refuse
 * it), integrates and records pantograph 1's lambda_p at every time point
 * and what @p request asks for.
 */
RunOutcome execute_study_run(const StudyRun& run, const Case& base,
                             const RunRequest& request);
} // namespace pantocat
