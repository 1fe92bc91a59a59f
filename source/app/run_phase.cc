#include <pantocat/app/run_phase.h>
#include <pantocat/io/run_summary.h>

#include <algorithm>
#include <filesystem>

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
                                              "checkpoint.bin.tmp",
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
  namespace fs = std::filesystem;
  // What a resumed run goes on from stays: the checkpoint, the time series
  // (cut back to the checkpoint's step) and the VTU frames before it.
  const std::vector<std::string> kept =
      resuming ? std::vector<std::string>{"parameters.prm", "checkpoint.bin",
                                          "time_series.csv", "solution.pvd"}
               : std::vector<std::string>{"parameters.prm"};
  std::error_code error;
  for (const std::string& name : result_files())
    if (std::find(kept.begin(), kept.end(), name) == kept.end())
      fs::remove(fs::path(directory) / name, error);
  // With several pantographs: contact_force_over_x_pantograph_k.png.
  for (const auto& entry : fs::directory_iterator(directory, error))
  {
    const std::string name = entry.path().filename().string();
    if (name.rfind("contact_force_over_x_", 0) == 0 && entry.path().extension() == ".png")
      fs::remove(entry.path(), error);
  }
  const fs::path frames = fs::path(directory) / "vtu";
  if (!resuming && fs::is_directory(frames, error))
    for (const auto& entry : fs::directory_iterator(frames, error))
      if (entry.path().extension() == ".vtu")
        fs::remove(entry.path(), error);
}

void RunPhase::begin(const std::string& next)
{
  const bool first = phase == "setup";
  phase = next;
  if (!first)
    return;
  clear_earlier_results();
  write_failed_summary(directory + "/summary.json", phase,
                       "the run has not finished: it is running, or it was killed");
  wrote_summary = true;
}

void RunPhase::refused()
{
  std::error_code error;
  if (wrote_summary)
    std::filesystem::remove(directory + "/summary.json", error);
}

void RunPhase::fail(const std::string& reason)
{
  if (phase != "study")
    clear_earlier_results();
  write_failed_summary(directory + "/summary.json", phase, reason);
}
} // namespace pantocat
