#include <pantocat/base/input_error.h>
#include <pantocat/simulation/checkpoint.h>
#include <pantocat/time/dynamic_state_serialization.h>

#include <boost/archive/archive_exception.hpp>

#include <algorithm>
#include <filesystem>
#include <sstream>

namespace pantocat
{
namespace
{
/// Written first: a file that does not start with it is no checkpoint of ours.
const std::string checkpoint_magic = "pantocat-fem checkpoint 1";

bool is_critical(const std::string& name)
{
  for (const char* prefix : {"Checkpoint/", "Study/", "Eigenfrequencies/"})
    if (name.rfind(prefix, 0) == 0)
      return false;
  for (const char* entry : {"Output/Output directory", "Output/Verbosity", "Output/Plots",
                            "Time integration/Force step size"})
    if (name == entry)
      return false;
  return true;
}

std::string trim(const std::string& s)
{
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string::npos)
    return "";
  return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}
} // namespace

ParameterFingerprint critical_parameters(const dealii::ParameterHandler& prm)
{
  // The resolved parameters as ShortPRM text: "subsection X", "set A = B", "end".
  std::ostringstream text;
  prm.print_parameters(text, dealii::ParameterHandler::ShortPRM);
  std::istringstream lines(text.str());
  std::vector<std::string> path;
  ParameterFingerprint list;
  for (std::string line; std::getline(lines, line);)
  {
    line = trim(line);
    if (line.rfind("subsection ", 0) == 0)
      path.push_back(trim(line.substr(11)));
    else if (line == "end" && !path.empty())
      path.pop_back();
    else if (line.rfind("set ", 0) == 0 && line.find('=') != std::string::npos)
    {
      const auto eq = line.find('=');
      std::string name;
      for (const auto& p : path)
        name += p + '/';
      name += trim(line.substr(4, eq - 4));
      if (is_critical(name))
        list.emplace_back(name, trim(line.substr(eq + 1)));
    }
  }
  return list;
}

void SimulationObserver::save(CheckpointOut&) const
{
  throw SimulationError("an observer of this run cannot write checkpoints");
}

void SimulationObserver::resume(const SimulationLayout&, CheckpointIn&)
{
  throw SimulationError("an observer of this run cannot resume from checkpoints");
}

CheckpointWriter::CheckpointWriter(std::string file, ParameterFingerprint f)
    : file_name(std::move(file)), fingerprint(std::move(f))
{
}

void CheckpointWriter::write(const unsigned long step, const TimeIntegrator& integrator,
                             const std::vector<SimulationObserver*>& observers) const
{
  const std::string temporary = file_name + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    CheckpointOut archive(out);
    archive << checkpoint_magic << fingerprint << step;
    integrator.save(archive);
    const auto n = static_cast<unsigned long>(std::count_if(
        observers.begin(), observers.end(), [](auto* o) { return o->checkpointed(); }));
    archive << n;
    for (const auto* o : observers)
      if (o->checkpointed())
        o->save(archive);
    out.flush();
    if (!out)
      throw SimulationError("cannot write the checkpoint " + temporary);
  }
  std::error_code error;
  std::filesystem::rename(temporary, file_name, error); // atomic on POSIX
  if (error)
    throw SimulationError("cannot rename " + temporary + " to " + file_name + ": " +
                          error.message());
}

CheckpointReader::CheckpointReader(const std::string& file,
                                   const ParameterFingerprint& fingerprint)
    : file_name(file), in(file, std::ios::binary)
{
  const std::string parameter = "Checkpoint/Resume from checkpoint = true";
  if (!in)
    throw InputError(parameter + ": there is no checkpoint " + file +
                     " (write one with Checkpoint/Interval > 0)");
  ParameterFingerprint saved;
  try
  {
    archive = std::make_unique<CheckpointIn>(in);
    std::string magic;
    *archive >> magic;
    if (magic != checkpoint_magic)
      throw InputError("");
    *archive >> saved >> steps;
  }
  catch (const std::exception&)
  {
    throw InputError(parameter + ": " + file +
                     " is not a checkpoint of this version of pantocat-fem, or it is "
                     "damaged");
  }
  // The first parameter that differs, or is only in one of the two lists.
  for (const auto& [name, value] : fingerprint)
  {
    const auto old = std::find_if(saved.begin(), saved.end(),
                                  [&](const auto& e) { return e.first == name; });
    const std::string old_value = old == saved.end() ? "(not set)" : old->second;
    if (old_value != value)
      throw InputError(parameter + ": the checkpoint " + file + " was made with " + name +
                       " = " + old_value + ", this run has " + value +
                       "; run with the checkpoint's value or start afresh");
  }
  for (const auto& [name, value] : saved)
    if (std::none_of(fingerprint.begin(), fingerprint.end(),
                     [&](const auto& e) { return e.first == name; }))
      throw InputError(parameter + ": the checkpoint " + file + " was made with " + name +
                       " = " + value + ", which this version does not know");
}

CheckpointReader::~CheckpointReader() = default;

void CheckpointReader::restore(TimeIntegrator& integrator, const SimulationLayout& layout,
                               const std::vector<SimulationObserver*>& observers)
{
  try
  {
    integrator.load(*archive);
    unsigned long n = 0;
    *archive >> n;
    const auto expected = static_cast<unsigned long>(std::count_if(
        observers.begin(), observers.end(), [](auto* o) { return o->checkpointed(); }));
    if (n != expected)
      throw SimulationError("the checkpoint " + file_name + " holds " +
                            std::to_string(n) + " outputs, this run has " +
                            std::to_string(expected));
    for (auto* o : observers)
      if (o->checkpointed())
        o->resume(layout, *archive);
      else
        o->start(layout);
  }
  catch (const boost::archive::archive_exception& e)
  {
    throw SimulationError("cannot read the checkpoint " + file_name + ": " + e.what());
  }
}
} // namespace pantocat
