#include <pantocat/base/input_error.h>
#include <pantocat/base/safe_files.h>
#include <pantocat/base/serialization.h>
#include <pantocat/io/csv_number.h>
#include <pantocat/io/time_series_writer.h>

#include <sstream>

namespace pantocat
{
TimeSeriesWriter::TimeSeriesWriter(const std::string& file, const unsigned int every_n)
    : file_name(file), every(std::max(1u, every_n))
{
}

std::vector<std::string> TimeSeriesWriter::contact_columns(const PantographLayout& p,
                                                           const std::string& column)
{
  std::vector<std::string> names;
  for (std::size_t w = 0; w < p.wire_contacts.size(); ++w)
    names.push_back(column + p.column_suffix +
                    (p.wire_contacts.size() > 1 ? "_w" + std::to_string(w + 1) : ""));
  return names;
}

std::vector<std::string> TimeSeriesWriter::column_names(const SimulationLayout& l)
{
  std::vector<std::string> names{"t"};
  const auto contacts = l.contacts();
  const auto each_contact = [&](const std::string& column)
  {
    for (const PantographLayout* p : contacts)
      for (const std::string& name : contact_columns(*p, column))
        names.push_back(name);
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

void TimeSeriesWriter::take_layout(const SimulationLayout& l)
{
  layout = l;
  contacts.clear();
  for (const PantographLayout* c : l.contacts())
    for (const unsigned int i : c->wire_contacts)
      contacts.push_back(i);
}

void TimeSeriesWriter::start(const SimulationLayout& l)
{
  take_layout(l);
  out.emplace(file_name);
  out->precision(10);
  const auto names = column_names(l);
  for (std::size_t i = 0; i < names.size(); ++i)
    *out << (i ? "," : "") << names[i];
  *out << '\n';
}

namespace
{
/// Writes "," and @p x as printf's %.10g writes it (the stream's precision
/// 10), without the stream's locale and formatting machinery:
/// write_csv_number(), the same text as std::to_chars in under half its time.
char* append(char* p, const double x)
{
  *p++ = ',';
  return write_csv_number(p, x);
}

/// Writes "," and the flag @p active as 1 or 0.
char* append_flag(char* p, const bool active)
{
  *p++ = ',';
  *p++ = active ? '1' : '0';
  return p;
}
} // namespace

void TimeSeriesWriter::observe(const TimePoint& p)
{
  reopen_after_resume();
  if (seen++ % every != 0)
    return;
  // One row, formatted into a buffer of its longest length and handed to the
  // stream's own buffer: the file is written in blocks, not row by row
  // (flushed at a checkpoint and at the end). No allocation per row: a
  // number takes at most 17 characters and its comma (write_csv_number()).
  const std::size_t numbers = 3 + p.x_p.size() + p.pantograph.size() + p.probes.size() +
                              3 * (contacts.size() + layout.dropper_indices.size()) +
                              (layout.energy ? 1 : 0);
  if (row.size() < 18 * numbers + 1)
    row.resize(18 * numbers + 1);
  char* end = write_csv_number(row.data(), p.t);
  for (const double x : p.x_p)
    end = append(end, x);
  for (const unsigned int c : contacts)
    end = append(end, p.lambda[c]);
  for (const unsigned int i : layout.dropper_indices)
    end = append(end, p.lambda[i]);
  for (const double w : p.pantograph)
    end = append(end, w);
  for (const unsigned int c : contacts)
    end = append(end, p.gap[c]);
  for (const unsigned int i : layout.dropper_indices)
    end = append(end, p.gap[i]);
  for (const unsigned int c : contacts)
    end = append_flag(end, p.active[c]);
  for (const unsigned int i : layout.dropper_indices)
    end = append_flag(end, p.active[i]);
  end = append(end, p.position_residual);
  end = append(end, p.velocity_residual);
  for (const double w : p.probes)
    end = append(end, w);
  if (layout.energy)
    end = append(end, p.energy);
  *end++ = '\n';
  out->write(row.data(), end - row.data());
}

void TimeSeriesWriter::finish()
{
  reopen_after_resume();
  out->close(); // throws, naming the file and the reason, if a write failed
}

void TimeSeriesWriter::save(CheckpointOut& archive) const
{
  if (!out) // resumed, no point seen since: the length it was cut to
  {
    archive << seen << resume_length.value_or(0ul);
    return;
  }
  out->check();
  const auto length = static_cast<unsigned long>(out->tellp());
  archive << seen << length;
}

void TimeSeriesWriter::resume(const SimulationLayout& l, CheckpointIn& archive)
{
  take_layout(l);
  unsigned long length = 0;
  archive >> seen >> length;
  const RegularFile file = regular_file(file_name);
  if (!file.size)
    throw InputError(file_name + " " + file.problem);
  if (*file.size < length)
    throw InputError(file_name + " is shorter than at the checkpoint (" +
                     std::to_string(length) + " bytes)");
  resume_length = length;
}

void TimeSeriesWriter::reopen_after_resume()
{
  if (!resume_length)
    return;
  out.emplace(file_name, OutputFile::Append{resume_length});
  resume_length.reset();
  out->precision(10);
}
} // namespace pantocat
