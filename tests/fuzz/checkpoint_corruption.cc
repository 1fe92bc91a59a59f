// Checkpoint corruption: a short half-explicit run is stopped after a
// checkpoint; then single bits of checkpoint.bin are flipped, one case at a
// time, and the run is resumed from it. Each case must either be refused
// (exit status 2, exactly one line on stderr that names the checkpoint file,
// time_series.csv and checkpoint.bin left as they were) or, if the flipped
// bit does not matter, resume to the results of the uninterrupted run, bit
// for bit. Fixed seed; the bits are spread over header and payload.
//
//   checkpoint_corruption EXE PRM WORKDIR FLIPS [SEED]
//   (FLIPS = 0: every byte of the file once, each with a random bit)
#include "child_process.h"

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <random>

namespace fs = std::filesystem;

namespace
{
/// The run: benchmark-32 on FDM N+1 = 125, to x_p = 2.5 m (313 steps of 5e-5 s),
/// checkpoints every 100 steps.
std::vector<std::string> run_arguments(const std::string& prm, const std::string& dir)
{
  return {prm,
          "--set",
          "Discretisation/Method=fdm",
          "--set",
          "Discretisation/Number of intervals=125",
          "--set",
          "Pantograph/Final position=2.5",
          "--set",
          "Output/Plots=false",
          "--set",
          "Output/Verbosity=quiet",
          "--set",
          "Checkpoint/Interval=100",
          "-o",
          dir};
}

std::vector<std::string> with(std::vector<std::string> arguments,
                              const std::string& setting)
{
  arguments.push_back("--set");
  arguments.push_back(setting);
  return arguments;
}

/// summary.json without its timing line, which differs from run to run, and
/// without the inputs that say how the run was stopped, resumed and written.
std::string summary_without_timing(const fs::path& file)
{
  std::string kept;
  for (const auto& line : fuzz::lines_of(fuzz::read_file(file.string())))
    if (line.find("time_loop_seconds") == std::string::npos &&
        line.find("\"Checkpoint/") == std::string::npos &&
        line.find("\"Output/Output directory\"") == std::string::npos)
      kept += line + '\n';
  return kept;
}

bool same_results(const fs::path& a, const fs::path& b)
{
  for (const char* file : {"time_series.csv", "contact_force.csv"})
    if (fuzz::read_file((a / file).string()) != fuzz::read_file((b / file).string()))
      return false;
  return summary_without_timing(a / "summary.json") ==
         summary_without_timing(b / "summary.json");
}

/// What a refusal's line says is wrong: the words after "is damaged: " or the like.
std::string refusal_kind(const std::string& line)
{
  for (const char* kind :
       {"checksum", "announces", "not a checkpoint", "ends inside its header",
        "was made with", "step", "cannot be read"})
    if (line.find(kind) != std::string::npos)
      return kind;
  return "other";
}

/// The positions to flip: each header byte once, then uniformly over the file;
/// or every byte if @p flips is 0.
std::vector<std::pair<std::size_t, int>> flips_of(const std::size_t size,
                                                  const std::size_t header,
                                                  const std::size_t flips,
                                                  const unsigned int seed)
{
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> bit(0, 7);
  std::uniform_int_distribution<std::size_t> position(0, size - 1);
  std::vector<std::pair<std::size_t, int>> list;
  if (flips == 0)
    for (std::size_t p = 0; p < size; ++p)
      list.emplace_back(p, bit(random));
  else
    for (std::size_t k = 0; k < flips; ++k)
      list.emplace_back(k < header && k < flips / 2 ? k : position(random), bit(random));
  return list;
}

void copy_directory(const fs::path& from, const fs::path& to)
{
  fs::remove_all(to);
  fs::copy(from, to, fs::copy_options::recursive);
}
} // namespace

int main(int argc, char** argv)
{
  if (argc < 5)
  {
    std::cerr << "usage: checkpoint_corruption EXE PRM WORKDIR FLIPS [SEED]\n";
    return 2;
  }
  const std::string exe = fs::absolute(argv[1]).string();
  const std::string prm = fs::absolute(argv[2]).string();
  const fs::path work = fs::absolute(argv[3]);
  const std::size_t n_flips = std::strtoul(argv[4], nullptr, 10);
  const unsigned int seed = argc > 5 ? std::strtoul(argv[5], nullptr, 10) : 20241;
  fs::remove_all(work);
  fs::create_directories(work);
  const double limit = 60.;

  const auto whole = fuzz::run(exe, run_arguments(prm, "whole"), work.string(),
                               (work / "whole").string(), limit);
  const auto stopped = fuzz::run(
      exe, with(run_arguments(prm, "stopped"), "Checkpoint/Stop after steps=250"),
      work.string(), (work / "stopped").string(), limit);
  if (whole.exit_status != 0 || stopped.exit_status != 1)
  {
    std::cerr << "setup: the uninterrupted run exited " << whole.exit_status
              << ", the stopped run " << stopped.exit_status << "\n"
              << whole.err << stopped.err;
    return 1;
  }
  const std::string intact = fuzz::read_file((work / "stopped/checkpoint.bin").string());
  const std::string series = fuzz::read_file((work / "stopped/time_series.csv").string());
  const std::size_t header = std::string("pantocat-fem checkpoint 5\n").size() + 12;

  // The intact checkpoint resumes to the uninterrupted run's results.
  copy_directory(work / "stopped", work / "case");
  const auto resume_arguments =
      with(run_arguments(prm, "case"), "Checkpoint/Resume from checkpoint=true");
  const auto resumed =
      fuzz::run(exe, resume_arguments, work.string(), (work / "resumed").string(), limit);
  if (resumed.exit_status != 0 || !same_results(work / "case", work / "whole"))
  {
    std::cerr << "setup: resuming the intact checkpoint did not give the uninterrupted "
                 "run's results (exit "
              << resumed.exit_status << ")\n"
              << resumed.err;
    return 1;
  }

  unsigned int refused = 0, identical = 0, failed = 0, in_header = 0;
  std::map<std::string, unsigned int> kinds;
  double slowest = 0.;
  const auto list = flips_of(intact.size(), header, n_flips, seed);
  for (const auto& [position, bit] : list)
  {
    in_header += position < header;
    copy_directory(work / "stopped", work / "case");
    std::string damaged = intact;
    damaged[position] = static_cast<char>(damaged[position] ^ (1 << bit));
    std::ofstream(work / "case/checkpoint.bin", std::ios::binary) << damaged;
    const auto o =
        fuzz::run(exe, resume_arguments, work.string(), (work / "flip").string(), limit);
    slowest = std::max(slowest, o.seconds);
    const auto lines = fuzz::lines_of(o.err);
    const bool one_line_naming_file =
        lines.size() == 1 && lines[0].rfind("pantocat-fem: error: ", 0) == 0 &&
        lines[0].find("case/checkpoint.bin") != std::string::npos;
    const bool untouched =
        fuzz::read_file((work / "case/time_series.csv").string()) == series &&
        fuzz::read_file((work / "case/checkpoint.bin").string()) == damaged;
    if (o.exit_status == 2 && one_line_naming_file && untouched)
    {
      ++refused;
      ++kinds[refusal_kind(lines[0])];
    }
    else if (o.exit_status == 0 && same_results(work / "case", work / "whole"))
      ++identical;
    else
    {
      ++failed;
      std::cout << "FAILED: byte " << position << " bit " << bit << ": exit "
                << o.exit_status
                << (o.signal ? " signal " + std::to_string(o.signal) : "")
                << (o.timed_out ? " (time limit)" : "")
                << (untouched ? "" : " (outputs changed)") << "\n"
                << o.err;
    }
  }
  std::cout << "checkpoint.bin: " << intact.size() << " bytes (header " << header << "); "
            << list.size() << " bit flips (" << in_header << " in the header), seed "
            << seed << "\n"
            << "  refused (exit 2, one line naming the file, outputs untouched): "
            << refused << "\n";
  for (const auto& [kind, count] : kinds)
    std::cout << "    " << kind << ": " << count << "\n";
  std::cout << "  resumed to the uninterrupted run's results: " << identical << "\n"
            << "  slowest case: " << slowest << " s\n"
            << list.size() - failed << " passed, " << failed << " failed\n";
  return failed == 0 ? 0 : 1;
}
