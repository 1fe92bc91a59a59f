#include <pantocat/base/input_error.h>
#include <pantocat/io/time_series_writer.h>

namespace pantocat
{
TimeSeriesWriter::TimeSeriesWriter(const std::string& file, const unsigned int every_n)
    : file_name(file), out(file), every(std::max(1u, every_n))
{
  if (!out)
    throw SimulationError("cannot write " + file);
  out.precision(10);
}

void TimeSeriesWriter::start(const SimulationLayout& l)
{
  layout = l;
  out << "t,x_p,lambda_p";
  for (unsigned int j = 0; j < l.dropper_indices.size(); ++j)
    out << ",lambda_d" << j + 1;
  for (const auto& name : l.pantograph_coordinates)
    out << ',' << name;
  out << ",gap_p";
  for (unsigned int j = 0; j < l.dropper_indices.size(); ++j)
    out << ",gap_d" << j + 1;
  out << ",active_p";
  for (unsigned int j = 0; j < l.dropper_indices.size(); ++j)
    out << ",active_d" << j + 1;
  out << ",residual_position,residual_velocity\n";
}

void TimeSeriesWriter::observe(const TimePoint& p)
{
  if (seen++ % every != 0)
    return;
  const unsigned int c = layout.contact_index;
  out << p.t << ',' << p.x_p << ',' << p.lambda[c];
  for (const unsigned int i : layout.dropper_indices)
    out << ',' << p.lambda[i];
  for (const double w : p.pantograph)
    out << ',' << w;
  out << ',' << p.gap[c];
  for (const unsigned int i : layout.dropper_indices)
    out << ',' << p.gap[i];
  out << ',' << p.active[c];
  for (const unsigned int i : layout.dropper_indices)
    out << ',' << p.active[i];
  out << ',' << p.position_residual << ',' << p.velocity_residual << '\n';
  out.flush();
}

void TimeSeriesWriter::finish()
{
  out.flush();
  if (!out)
    throw SimulationError("writing " + file_name + " failed");
}
} // namespace pantocat
