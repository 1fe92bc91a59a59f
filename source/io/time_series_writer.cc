#include <pantocat/base/input_error.h>
#include <pantocat/base/serialization.h>
#include <pantocat/io/time_series_writer.h>

#include <filesystem>

namespace pantocat
{
TimeSeriesWriter::TimeSeriesWriter(const std::string& file, const unsigned int every_n)
    : file_name(file), every(std::max(1u, every_n))
{
}

void TimeSeriesWriter::start(const SimulationLayout& l)
{
  layout = l;
  out.open(file_name);
  if (!out)
    throw SimulationError("cannot write " + file_name);
  out.precision(10);
  const bool contact = l.has_contact();
  out << "t,x_p" << (contact ? ",lambda_p" : "");
  for (unsigned int j = 0; j < l.dropper_indices.size(); ++j)
    out << ",lambda_d" << j + 1;
  for (const auto& name : l.pantograph_coordinates)
    out << ',' << name;
  out << (contact ? ",gap_p" : "");
  for (unsigned int j = 0; j < l.dropper_indices.size(); ++j)
    out << ",gap_d" << j + 1;
  out << (contact ? ",active_p" : "");
  for (unsigned int j = 0; j < l.dropper_indices.size(); ++j)
    out << ",active_d" << j + 1;
  out << ",residual_position,residual_velocity";
  for (const double x : l.probe_positions)
    out << ",w_w(" << x << ')';
  out << (l.energy ? ",energy" : "") << '\n';
}

void TimeSeriesWriter::observe(const TimePoint& p)
{
  reopen_after_resume();
  if (seen++ % every != 0)
    return;
  const unsigned int c = layout.contact_index;
  const bool contact = layout.has_contact();
  out << p.t << ',' << p.x_p;
  if (contact)
    out << ',' << p.lambda[c];
  for (const unsigned int i : layout.dropper_indices)
    out << ',' << p.lambda[i];
  for (const double w : p.pantograph)
    out << ',' << w;
  if (contact)
    out << ',' << p.gap[c];
  for (const unsigned int i : layout.dropper_indices)
    out << ',' << p.gap[i];
  if (contact)
    out << ',' << p.active[c];
  for (const unsigned int i : layout.dropper_indices)
    out << ',' << p.active[i];
  out << ',' << p.position_residual << ',' << p.velocity_residual;
  for (const double w : p.probes)
    out << ',' << w;
  if (layout.energy)
    out << ',' << p.energy;
  out << '\n';
  out.flush();
}

void TimeSeriesWriter::finish()
{
  reopen_after_resume();
  out.flush();
  if (!out)
    throw SimulationError("writing " + file_name + " failed");
}

void TimeSeriesWriter::save(CheckpointOut& archive) const
{
  out.flush();
  const auto length = static_cast<unsigned long>(out.tellp());
  archive << seen << length;
}

void TimeSeriesWriter::resume(const SimulationLayout& l, CheckpointIn& archive)
{
  layout = l;
  unsigned long length = 0;
  archive >> seen >> length;
  std::error_code error;
  const auto size = std::filesystem::file_size(file_name, error);
  if (error || size < length)
    throw InputError(file_name + " is shorter than at the checkpoint (" +
                     std::to_string(length) + " bytes)");
  resume_length = length;
}

void TimeSeriesWriter::reopen_after_resume()
{
  if (!resume_length)
    return;
  std::error_code error;
  std::filesystem::resize_file(file_name, *resume_length, error);
  resume_length.reset();
  out.open(file_name, std::ios::app);
  if (error || !out)
    throw SimulationError("cannot resume writing " + file_name);
  out.precision(10);
}
} // namespace pantocat
