#include <pantocat/base/input_error.h>
#include <pantocat/base/safe_files.h>
#include <pantocat/simulation/checkpoint.h>
#include <pantocat/time/dynamic_state_serialization.h>

#include <deal.II/base/utilities.h>

#include <boost/crc.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <sstream>

namespace pantocat
{
namespace
{
/**
 * The file starts with this line, then the length of the payload (8 bytes)
 * and its CRC-32 (4 bytes), little endian; the payload, a Boost binary
 * archive, follows. Version 4 (without the pantographs' contact-loss
 * intervals over all their contact wires), version 3 (without the positions
 * of the force extremes),
 * version 2 (without the impulses of DynamicState) and version 1 (a Boost
 * archive that began with its own magic string, without length or
 * checksum) are no longer read.
 */
const std::string checkpoint_magic = "pantocat-fem checkpoint 5\n";
const std::size_t header_size = checkpoint_magic.size() + 8 + 4;
/// A checkpoint holds the state and the observers' records: far below this.
constexpr std::uint64_t max_checkpoint_bytes = std::uint64_t(4) << 30;

std::uint32_t crc32_of(const std::string& bytes)
{
  boost::crc_32_type crc;
  crc.process_bytes(bytes.data(), bytes.size());
  return crc.checksum();
}

template <typename Integer>
void append_little_endian(std::string& bytes, Integer value, const unsigned int n)
{
  for (unsigned int i = 0; i < n; ++i, value >>= 8)
    bytes += static_cast<char>(value & 0xff);
}

template <typename Integer>
Integer read_little_endian(const std::string& bytes, const std::size_t at,
                           const unsigned int n)
{
  Integer value = 0;
  for (unsigned int i = n; i-- > 0;)
    value = (value << 8) | static_cast<unsigned char>(bytes[at + i]);
  return value;
}

bool is_critical(const std::string& name)
{
  for (const char* prefix : {"Checkpoint/", "Study/", "Eigenfrequencies/", "Elasticity/"})
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

ParameterFingerprint resolved_parameters(const dealii::ParameterHandler& prm)
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
      list.emplace_back(name, trim(line.substr(eq + 1)));
    }
  }
  return list;
}

ParameterFingerprint critical_parameters(const dealii::ParameterHandler& prm)
{
  ParameterFingerprint list = resolved_parameters(prm);
  list.erase(std::remove_if(list.begin(), list.end(),
                            [](const auto& e) { return !is_critical(e.first); }),
             list.end());
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
  std::ostringstream payload;
  {
    CheckpointOut archive(payload);
    archive << fingerprint << step;
    integrator.save(archive);
    const auto n = static_cast<unsigned long>(std::count_if(
        observers.begin(), observers.end(), [](auto* o) { return o->checkpointed(); }));
    archive << n;
    for (const auto* o : observers)
      if (o->checkpointed())
        o->save(archive);
  }
  const std::string bytes = payload.str();
  std::string header = checkpoint_magic;
  append_little_endian(header, static_cast<std::uint64_t>(bytes.size()), 8);
  append_little_endian(header, crc32_of(bytes), 4);

  write_file_atomically(file_name, header + bytes);
}

CheckpointReader::CheckpointReader(const std::string& file,
                                   const ParameterFingerprint& fingerprint,
                                   const unsigned long run_steps, const double dt)
    : file_name(file), time_step(dt)
{
  // Not through a link, not a FIFO or device (read at once, never waited on).
  const FileContent content = read_regular_file(file, max_checkpoint_bytes, false);
  if (content.missing)
    throw InputError(refusal() + "there is no checkpoint " + file +
                     " (write one with Checkpoint/Interval > 0)");
  if (!content.bytes)
    throw InputError(refusal() + "the checkpoint " + file + " " + content.problem +
                     "; start afresh (Resume from checkpoint = false)");
  payload.str(verified_payload(*content.bytes));
  ParameterFingerprint saved;
  try
  {
    archive = std::make_unique<CheckpointIn>(payload);
    *archive >> saved >> steps;
  }
  catch (const std::exception& e)
  {
    throw damaged(std::string("its parameters cannot be read (") + e.what() + ")");
  }
  check_fingerprint(saved, fingerprint);
  if (steps == 0 || steps >= run_steps)
    throw damaged("it was written after step " + std::to_string(steps) +
                  ", but a checkpoint lies between step 1 and the run's last step " +
                  std::to_string(run_steps));
}

CheckpointReader::~CheckpointReader() = default;

std::string CheckpointReader::refusal()
{
  return "Checkpoint/Resume from checkpoint = true: ";
}

InputError CheckpointReader::damaged(const std::string& what) const
{
  return InputError(refusal() + "the checkpoint " + file_name + " is damaged: " + what +
                    "; start afresh (Resume from checkpoint = false)");
}

std::string CheckpointReader::verified_payload(const std::string& bytes) const
{
  if (bytes.compare(0, checkpoint_magic.size(), checkpoint_magic) != 0)
    throw InputError(refusal() + file_name +
                     " is not a checkpoint of this version of pantocat-fem (it does not "
                     "start with \"pantocat-fem checkpoint 5\"), or it is damaged");
  if (bytes.size() < header_size)
    throw damaged("it ends inside its header");
  const auto length =
      read_little_endian<std::uint64_t>(bytes, checkpoint_magic.size(), 8);
  const auto checksum =
      read_little_endian<std::uint32_t>(bytes, checkpoint_magic.size() + 8, 4);
  if (length != bytes.size() - header_size)
    throw damaged("its header announces " + std::to_string(length) +
                  " bytes of data, the file holds " +
                  std::to_string(bytes.size() - header_size));
  std::string data = bytes.substr(header_size);
  if (crc32_of(data) != checksum)
    throw damaged("its checksum (CRC-32) does not match its data");
  return data;
}

void CheckpointReader::check_fingerprint(const ParameterFingerprint& saved,
                                         const ParameterFingerprint& fingerprint) const
{
  // The first parameter that differs, or is only in one of the two lists.
  for (const auto& [name, value] : fingerprint)
  {
    const auto old = std::find_if(saved.begin(), saved.end(),
                                  [&](const auto& e) { return e.first == name; });
    const std::string old_value = old == saved.end() ? "(not set)" : old->second;
    if (old_value != value)
      throw InputError(refusal() + "the checkpoint " + file_name + " was made with " +
                       name + " = " + old_value + ", this run has " + value +
                       "; run with the checkpoint's value or start afresh");
  }
  for (const auto& [name, value] : saved)
    if (std::none_of(fingerprint.begin(), fingerprint.end(),
                     [&](const auto& e) { return e.first == name; }))
      throw InputError(refusal() + "the checkpoint " + file_name + " was made with " +
                       name + " = " + value + ", which this version does not know");
}

void CheckpointReader::restore(TimeIntegrator& integrator, const SimulationLayout& layout,
                               const std::vector<SimulationObserver*>& observers)
{
  try
  {
    const double t0 = integrator.time();
    integrator.load(*archive);
    check_integrator(integrator, t0);
    unsigned long n = 0;
    *archive >> n;
    const auto expected = static_cast<unsigned long>(std::count_if(
        observers.begin(), observers.end(), [](auto* o) { return o->checkpointed(); }));
    if (n != expected)
      throw InputError("it holds " + std::to_string(n) + " outputs, this run has " +
                       std::to_string(expected));
    for (auto* o : observers)
      if (o->checkpointed())
        o->resume(layout, *archive);
      else
        o->start(layout);
    if (payload.peek() != std::char_traits<char>::eof())
      throw InputError("it holds more data than this run reads");
  }
  catch (const std::exception& e)
  {
    throw InputError(refusal() + "the checkpoint " + file_name + " cannot be resumed: " +
                     e.what() + "; start afresh (Resume from checkpoint = false)");
  }
}

void CheckpointReader::check_integrator(const TimeIntegrator& integrator,
                                        const double t0) const
{
  if (integrator.statistics().steps != steps)
    throw InputError("its integrator counted " +
                     std::to_string(integrator.statistics().steps) +
                     " steps, its header says " + std::to_string(steps));
  const double dt = time_step;
  if (std::isfinite(dt) && !(std::abs(integrator.time() - (t0 + steps * dt)) <= 0.5 * dt))
  {
    std::ostringstream m;
    m << "its time " << integrator.time() << " s is not that of step " << steps << " ("
      << t0 + steps * dt << " s)";
    throw InputError(m.str());
  }
}
} // namespace pantocat
