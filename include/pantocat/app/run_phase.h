#pragma once

#include <pantocat/io/run_summary.h>

#include <optional>
#include <string>
#include <vector>

namespace pantocat
{
/// The files a run of some mode may write into its output directory (README).
const std::vector<std::string>& result_files();

/**
 * Where a run is, so that every way it can fail leaves a summary.json that
 * says "failed", in which phase and why, and nothing of an earlier run that
 * could pass for its own (doc/output.md):
 * - it starts in "setup" (assembly, the initial state, checks); a refusal
 *   there (InputError) leaves the directory as it was;
 * - begin() of the first later phase clears the earlier run's results
 *   (resumed: keeps the checkpoint, the time series and the VTU frames the
 *   run goes on from) and writes summary.json "failed" in that phase, "not
 *   finished", which the completed summary replaces at the end: a run that is
 *   killed is never taken for a completed one;
 * - fail() writes summary.json "failed" with the phase and the reason (in
 *   "setup" after clearing the earlier results); refused() removes begin()'s
 *   summary.json again for a refusal, or, for a refused resume, puts back
 *   the stopped run's summary.json that begin() replaced.
 * An earlier result that cannot be removed is an error (SimulationError
 * naming the file); nothing is removed through a link (vtu/ a link: left
 * alone).
 */
class RunPhase
{
public:
  RunPhase(std::string directory, bool resuming);

  /// Enters @p phase (time loop, output, static solve, ...).
  void begin(const std::string& phase);
  /**
   * Enters the phase "study": a study writes no summary.json when it
   * completes, so nothing is cleared or written here; fail() still writes one.
   */
  void begin_study() { phase = "study"; }
  /// summary.json "failed" with the current phase and @p reason (and the windows kept).
  void fail(const std::string& reason);
  /// Windows a run passed before it failed: fail() writes them into summary.json.
  void keep_passed_windows(std::vector<PassedWindow> windows)
  {
    passed_windows = std::move(windows);
  }
  /**
   * Undoes begin()'s summary.json for a refusal after the setup (a damaged
   * checkpoint is found when the time loop starts): a refusal leaves no
   * result, and the summary of a stopped run it refused to resume stays.
   */
  void refused();
  const std::string& name() const { return phase; }

private:
  void clear_earlier_results();

  std::string directory;
  bool resuming;
  std::string phase = "setup";
  bool cleared = false;
  bool wrote_summary = false;
  std::optional<std::string> earlier_summary; ///< summary.json before begin()
  std::vector<PassedWindow> passed_windows;
};
} // namespace pantocat
