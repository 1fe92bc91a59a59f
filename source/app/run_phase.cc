#include <pantocat/app/run_phase.h>
#include <pantocat/base/input_error.h>
#include <pantocat/base/safe_files.h>
#include <pantocat/io/run_summary.h>

#include <algorithm>

namespace pantocat
{
const std::vector<std::string>& result_files()
{
  static const std::vector<std::string> files{"parameters.prm",
                                              "summary.json",
                                              "time_series.csv",
                                              "contact_force.csv",
                                              "contact_force.png",
                                              "dropper_forces.png",
                                              "pantograph.png",
                                              "contact_force_statistics.png",
                                              "time_series.gp",
                                              "contact_force_statistics.gp",
                                              "contact_force_over_x.png",
                                              "contact_force_over_x.gp",
                                              "solution.pvd",
                                              "checkpoint.bin",
                                              "static_profile.csv",
                                              "static_profile.vtu",
                                              "dropper_forces.csv",
                                              "dropper_lengths.csv",
                                              "elasticity.gp",
                                              "elasticity.png",
                                              "elasticity.csv",
                                              "eigenfrequencies.csv",
                                              "convergence.txt",
                                              "convergence.csv",
                                              "work_precision.csv",
                                              "speed_sweep.csv",
                                              "parameter_sweep.csv",
                                              "monte_carlo.csv"};
  return files;
}

RunPhase::RunPhase(std::string dir, const bool resume)
    : directory(std::move(dir)), resuming(resume)
{
}

void RunPhase::clear_earlier_results()
{
  if (cleared)
    return;
  cleared = true;
  // What a resumed run goes on from stays: the checkpoint, the time series
  // (cut back to the checkpoint's step) and the VTU frames before it.
  const std::vector<std::string> kept =
      resuming ? std::vector<std::string>{"parameters.prm", "checkpoint.bin",
                                          "time_series.csv", "solution.pvd"}
               : std::vector<std::string>{"parameters.prm"};
  const auto& results = result_files();
  const auto is_result = [&](const std::string& name)
  { return std::find(results.begin(), results.end(), name) != results.end(); };
  const auto cleared_file = [&](const std::string& name)
  {
    // With several pantographs: contact_force_over_x_pantograph_k.png; and
    // the temporary files of whole-file writes that a killed run left.
    const auto temporary = name.find(".tmp-");
    return (is_result(name) && std::find(kept.begin(), kept.end(), name) == kept.end()) ||
           (name.rfind("contact_force_over_x_", 0) == 0 && name.size() > 4 &&
            name.compare(name.size() - 4, 4, ".png") == 0) ||
           (temporary != std::string::npos && is_result(name.substr(0, temporary)));
  };
  // A failure to remove is an error: a result left behind would pass for ours.
  const Directory output = Directory::open(directory);
  output.remove_files(cleared_file);
  // vtu/ only if it is a directory: a link there leads out of the output
  // directory, where nothing is removed (the VTU writer replaces the link).
  if (const auto frames = Directory::existing_subdirectory(output, "vtu");
      frames && !resuming)
    frames->remove_files(
        [](const std::string& name)
        { return name.size() > 4 && name.compare(name.size() - 4, 4, ".vtu") == 0; });
}

void RunPhase::begin(const std::string& next)
{
  const bool first = phase == "setup";
  phase = next;
  if (!first)
    return;
  // A refused resume (a checkpoint that cannot be resumed is found when the
  // time loop starts) puts back the summary of the run it refused to go on
  // with; not a "completed" one, whose results are cleared below.
  if (resuming)
    earlier_summary =
        read_regular_file(directory + "/summary.json", std::uint64_t(64) << 20, false)
            .bytes;
  if (earlier_summary &&
      earlier_summary->find("\"status\": \"completed\"") != std::string::npos)
    earlier_summary.reset();
  clear_earlier_results();
  write_failed_summary(directory + "/summary.json", phase,
                       "the run has not finished: it is running, or it was killed");
  wrote_summary = true;
}

void RunPhase::refused()
{
  if (!wrote_summary)
    return;
  try
  {
    if (earlier_summary)
      write_file_atomically(directory + "/summary.json", *earlier_summary);
    else
      remove_output(directory + "/summary.json");
  }
  catch (const SimulationError&)
  {
    // The refusal is what the run reports; its summary says "not finished".
  }
}

void RunPhase::fail(const std::string& reason)
{
  if (phase != "study")
    clear_earlier_results();
  write_failed_summary(directory + "/summary.json", phase, reason, passed_windows);
}
} // namespace pantocat
