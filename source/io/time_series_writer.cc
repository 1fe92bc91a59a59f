#include <pantocat/base/input_error.h>
#include <pantocat/base/serialization.h>
#include <pantocat/io/csv_number.h>
#include <pantocat/io/time_series_writer.h>

#include <filesystem>
#include <sstream>

namespace pantocat
{
TimeSeriesWriter::TimeSeriesWriter(const std::string& file, const unsigned int every_n)
    : file_name(file), every(std::max(1u, every_n))
{
}

std::vector<std::string> TimeSeriesWriter::column_names(const SimulationLayout& l)
{
  std::vector<std::string> names{"t"};
  const auto contacts = l.contacts();
  const auto each_contact = [&](const std::string& column)
  {
    for (const PantographLayout* p : contacts)
      names.push_back(column + p->column_suffix);
  };
  const auto each_dropper = [&](const std::string& column)
  {
    for (unsigned int j = 0; j < l.dropper_indices.size(); ++j)
      names.push_back(column + std::to_string(j + 1));
  };
  for (const PantographLayout& p : l.pantographs)
    names.push_back("x_p" + p.column_suffix);
  each_contact("lambda_p");
  each_dropper("lambda_d");
  for (const PantographLayout& p : l.pantographs)
    for (const auto& name : p.coordinates)
      names.push_back(name + p.column_suffix);
  each_contact("gap_p");
  each_dropper("gap_d");
  each_contact("active_p");
  each_dropper("active_d");
  names.push_back("residual_position");
  names.push_back("residual_velocity");
  for (const double x : l.probe_positions)
  {
    std::ostringstream name;
    name << "w_w(" << x << ')';
    names.push_back(name.str());
  }
  if (l.energy)
    names.push_back("energy");
  return names;
}

void TimeSeriesWriter::start(const SimulationLayout& l)
{
  layout = l;
  out.open(file_name);
  if (!out)
    throw SimulationError("cannot write " + file_name);
  out.precision(10);
  const auto names = column_names(l);
  for (std::size_t i = 0; i < names.size(); ++i)
    out << (i ? "," : "") << names[i];
  out << '\n';
}

namespace
{
/// Appends "," (unless @p first) and @p x as printf's %.10g writes it (the
/// stream's precision 10), without the stream's locale and formatting machinery:
/// write_csv_number(), the same text as std::to_chars in under half its time.
void append(std::string& line, const double x, const bool first = false)
{
  char buffer[32];
  char* p = buffer;
  if (!first)
    *p++ = ',';
  p = write_csv_number(p, x);
  line.append(buffer, p);
}
} // namespace

void TimeSeriesWriter::observe(const TimePoint& p)
{
  reopen_after_resume();
  if (seen++ % every != 0)
    return;
  // One row, formatted into a reused buffer and handed to the stream's own
  // buffer: the file is written in blocks, not row by row (flushed at a
  // checkpoint and at the end).
  const auto contacts = layout.contacts();
  line.clear();
  append(line, p.t, true);
  for (const double x : p.x_p)
    append(line, x);
  for (const PantographLayout* c : contacts)
    append(line, p.lambda[c->contact]);
  for (const unsigned int i : layout.dropper_indices)
    append(line, p.lambda[i]);
  for (const double w : p.pantograph)
    append(line, w);
  for (const PantographLayout* c : contacts)
    append(line, p.gap[c->contact]);
  for (const unsigned int i : layout.dropper_indices)
    append(line, p.gap[i]);
  for (const PantographLayout* c : contacts)
    line += p.active[c->contact] ? ",1" : ",0";
  for (const unsigned int i : layout.dropper_indices)
    line += p.active[i] ? ",1" : ",0";
  append(line, p.position_residual);
  append(line, p.velocity_residual);
  for (const double w : p.probes)
    append(line, w);
  if (layout.energy)
    append(line, p.energy);
  line += '\n';
  out.write(line.data(), line.size());
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
