#include <pantocat/base/input_error.h>
#include <pantocat/base/safe_files.h>
#include <pantocat/base/serialization.h>
#include <pantocat/io/vtu_time_series_writer.h>
#include <pantocat/space/catenary_discretisation.h>

#include <deal.II/base/data_out_base.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/numerics/data_out.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>

namespace pantocat
{
namespace
{
/// "wires-00012.vtu": the file of @p frame in vtu/.
std::string frame_name(const char* stem, const unsigned long frame)
{
  char name[64];
  std::snprintf(name, sizeof name, "%s-%05lu.vtu", stem, frame);
  return name;
}

/// True for the frames a run writes into vtu/.
bool is_frame(const std::string& name)
{
  return (name.rfind("wires-", 0) == 0 || name.rfind("pantograph-droppers-", 0) == 0) &&
         name.size() > 4 && name.compare(name.size() - 4, 4, ".vtu") == 0;
}

/// Runs @p write on @p out and closes it; a failed write names the file and why.
template <typename Write>
void write_frame(OutputFile& out, const Write& write)
{
  try
  {
    write(out);
  }
  catch (const dealii::ExceptionBase&)
  {
    out.close(); // throws with the file and the reason of a failed write
    throw;
  }
  out.close();
}

dealii::DataOutBase::VtkFlags flags_at(const double time)
{
  dealii::DataOutBase::VtkFlags flags;
  flags.time = time;
  flags.compression_level = dealii::DataOutBase::VtkFlags::best_speed;
  return flags;
}
} // namespace

VtuTimeSeriesWriter::VtuTimeSeriesWriter(const std::string& directory,
                                         const double interval, const double time_step,
                                         const unsigned int subdivisions,
                                         const CatenaryDiscretisation& d,
                                         const SemiDiscreteSystem& system,
                                         dealii::TimerOutput* timer)
    : directory(directory), interval(std::max(interval, time_step)),
      tolerance(0.5 * time_step), timer(timer),
      dropper_x(d.catenary_parameters().dropper_positions),
      support_height(d.catenary_parameters().support_height), sample_fe(1),
      sample_dofs(sample_mesh)
{
  // FDM unknowns are point values at the nodes (point_row is constant on each
  // control volume): sample there; FEM shows its shape functions between them.
  const unsigned int per_cell = d.method() == SpaceMethod::fdm ? 1 : subdivisions;
  dealii::GridGenerator::subdivided_hyper_cube(sample_mesh, d.n_intervals() * per_cell,
                                               0., d.catenary_parameters().length());
  sample_dofs.distribute_dofs(sample_fe);
  carrier_rows.resize(sample_dofs.n_dofs());
  wire_rows.resize(sample_dofs.n_dofs());
  for (const auto& cell : sample_dofs.active_cell_iterators())
    for (unsigned int v = 0; v < 2; ++v)
    {
      const double x = cell->vertex(v)[0];
      const auto i = cell->vertex_dof_index(v, 0);
      carrier_rows[i] = wire_point_row(d, system, Wire::carrier, x);
      wire_rows[i] = wire_point_row(d, system, Wire::contact_wire, x);
    }
  for (const double x : dropper_x)
    dropper_rows.push_back(wire_point_row(d, system, Wire::contact_wire, x));
}

void VtuTimeSeriesWriter::start(const SimulationLayout& l)
{
  layout = l;
  if (l.dropper_indices.empty()) // a scene without droppers
    dropper_rows.clear();
  next_frame = 0;
  written.clear();
  bool replaced_link = false;
  frames_directory.emplace(
      Directory::subdirectory(Directory::open(directory), "vtu", &replaced_link));
  if (replaced_link)
    std::cerr << "pantocat-fem: warning: " << frames_directory->path()
              << " was a symbolic link; it is replaced by a directory for the frames "
                 "(the link's target is left as it is)"
              << std::endl;
  // Frames of an earlier run into the same directory would look like ours.
  frames_directory->remove_files(is_frame);
}

void VtuTimeSeriesWriter::observe_state(const TimePoint& point, const DynamicState& state)
{
  if (point.t < next_frame * interval - tolerance)
    return;
  std::optional<dealii::TimerOutput::Scope> scope;
  if (timer)
    scope.emplace(*timer, "output: VTU frames");
  const unsigned long frame = written.size();
  const std::string wires = frame_name("wires", frame);
  write_wires(state, wires);
  write_points(point, state, frame_name("pantograph-droppers", frame));
  written.emplace_back(point.t, "vtu/" + wires);
  write_pvd();
  while (next_frame * interval - tolerance <= point.t)
    ++next_frame;
}

void VtuTimeSeriesWriter::write_wires(const DynamicState& s,
                                      const std::string& file) const
{
  const auto n = sample_dofs.n_dofs();
  dealii::Vector<double> w_c(n), w_w(n), v_c(n), v_w(n);
  for (unsigned int i = 0; i < n; ++i)
  {
    w_c(i) = support_height + carrier_rows[i].dot(s.q);
    w_w(i) = wire_rows[i].dot(s.q);
    v_c(i) = carrier_rows[i].dot(s.v);
    v_w(i) = wire_rows[i].dot(s.v);
  }
  dealii::DataOut<1> data_out;
  data_out.attach_dof_handler(sample_dofs);
  data_out.add_data_vector(w_c, "carrier_displacement");
  data_out.add_data_vector(w_w, "contact_wire_displacement");
  data_out.add_data_vector(v_c, "carrier_velocity");
  data_out.add_data_vector(v_w, "contact_wire_velocity");
  data_out.build_patches();
  data_out.set_flags(flags_at(s.t));
  OutputFile out(*frames_directory, file);
  write_frame(out, [&](std::ostream& o) { data_out.write_vtu(o); });
}

void VtuTimeSeriesWriter::write_points(const TimePoint& p, const DynamicState& s,
                                       const std::string& file) const
{
  std::vector<dealii::DataOutBase::Patch<0, 2>> patches;
  const auto add =
      [&](const double x, const double w, const unsigned int constraint, const double id)
  {
    dealii::DataOutBase::Patch<0, 2> patch;
    patch.vertices[0] = dealii::Point<2>(x, w);
    patch.patch_index = patches.size();
    patch.data.reinit(3, 1);
    patch.data(0, 0) = p.lambda[constraint];
    patch.data(1, 0) = p.active[constraint] ? 1. : 0.;
    patch.data(2, 0) = id;
    patches.push_back(patch);
  };
  // The heads (their first coordinate, b = w_p1) with id 0, -1, -2, ...
  for (unsigned int k = 0; k < layout.pantographs.size(); ++k)
  {
    const PantographLayout& pantograph = layout.pantographs[k];
    if (pantograph.has_contact())
      add(p.x_p[k], p.pantograph.at(pantograph.first_coordinate), pantograph.contact,
          k == 0 ? 0. : -static_cast<double>(k));
  }
  for (std::size_t j = 0; j < dropper_rows.size(); ++j)
    add(dropper_x[j], dropper_rows[j].dot(s.q), layout.dropper_indices[j], j + 1.);
  OutputFile out(*frames_directory, file);
  write_frame(out,
              [&](std::ostream& o)
              {
                dealii::DataOutBase::write_vtu(patches, {"force", "active", "id"}, {},
                                               flags_at(s.t), o);
              });
}

void VtuTimeSeriesWriter::write_pvd() const
{
  // Two parts per time step: ParaView opens them as one multiblock data set.
  std::ostringstream pvd;
  pvd << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <Collection>\n"
      << std::setprecision(12);
  for (std::size_t k = 0; k < written.size(); ++k)
  {
    pvd << "    <DataSet timestep=\"" << written[k].first
        << "\" group=\"\" part=\"0\" file=\"vtu/" << frame_name("wires", k) << "\"/>\n";
    pvd << "    <DataSet timestep=\"" << written[k].first
        << "\" group=\"\" part=\"1\" file=\"vtu/" << frame_name("pantograph-droppers", k)
        << "\"/>\n";
  }
  pvd << "  </Collection>\n</VTKFile>\n";
  write_file_atomically(directory + "/solution.pvd", pvd.str());
}

void VtuTimeSeriesWriter::save(CheckpointOut& archive) const
{
  archive << next_frame << written;
}

void VtuTimeSeriesWriter::resume(const SimulationLayout& l, CheckpointIn& archive)
{
  layout = l;
  archive >> next_frame >> written;
  // The frames written before the checkpoint stay; they must still be there.
  frames_directory = Directory::existing_subdirectory(Directory::open(directory), "vtu");
  for (unsigned long k = 0; k < written.size(); ++k)
    for (const char* stem : {"wires", "pantograph-droppers"})
      if (!frames_directory || !frames_directory->contains(frame_name(stem, k)))
        throw InputError("its frame " + directory + "/vtu/" + frame_name(stem, k) +
                         " is missing (" + directory + "/vtu was removed or changed)");
  if (!frames_directory)
    frames_directory.emplace(Directory::subdirectory(Directory::open(directory), "vtu"));
}
} // namespace pantocat
