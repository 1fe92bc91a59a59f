#include <pantocat/base/input_error.h>
#include <pantocat/base/safe_files.h>
#include <pantocat/io/wire_output.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>
#include <deal.II/numerics/data_out.h>

#include <iomanip>

namespace pantocat
{
dealii::Vector<double> block_values(const SemiDiscreteSystem& system,
                                    const dealii::Vector<double>& q,
                                    const std::string& name)
{
  const DofBlock& b = system.block(name);
  dealii::Vector<double> values(b.size);
  for (unsigned int i = 0; i < b.size; ++i)
    values(i) = q(b.first + i);
  return values;
}

void write_wire_profiles(const CatenaryDiscretisation& d,
                         const SemiDiscreteSystem& system,
                         const dealii::Vector<double>& q, const std::string& csv_file,
                         const std::string& vtu_file, const unsigned int subdivisions,
                         const double time)
{
  // A rigid carrier (no block) stays at the support height: u_c = 0.
  const dealii::Vector<double> qc = system.has_block("carrier")
                                        ? block_values(system, q, "carrier")
                                        : dealii::Vector<double>(d.n_dofs(Wire::carrier));
  const dealii::Vector<double> qw = block_values(system, q, "contact wire");

  OutputFile csv(csv_file);
  csv << "x_m,w_carrier_m,w_contact_wire_m\n" << std::setprecision(12);
  for (const double x : d.grid_points())
    csv << x << ',' << d.displacement(Wire::carrier, qc, x) << ','
        << d.displacement(Wire::contact_wire, qw, x) << '\n';
  csv.close();

  // VTU: sample both wires on a finer linear grid.
  dealii::Triangulation<1> tria;
  dealii::GridGenerator::subdivided_hyper_cube(tria, d.n_intervals() * subdivisions, 0.,
                                               d.catenary_parameters().length());
  dealii::FE_Q<1> fe(1);
  dealii::DoFHandler<1> dofs(tria);
  dofs.distribute_dofs(fe);
  dealii::Vector<double> carrier(dofs.n_dofs()), wire(dofs.n_dofs());
  for (const auto& cell : dofs.active_cell_iterators())
    for (unsigned int v = 0; v < 2; ++v)
    {
      const double x = cell->vertex(v)[0];
      carrier(cell->vertex_dof_index(v, 0)) = d.displacement(Wire::carrier, qc, x);
      wire(cell->vertex_dof_index(v, 0)) = d.displacement(Wire::contact_wire, qw, x);
    }
  dealii::DataOut<1> data_out;
  data_out.attach_dof_handler(dofs);
  data_out.add_data_vector(carrier, "carrier_displacement");
  data_out.add_data_vector(wire, "contact_wire_displacement");
  data_out.build_patches();
  dealii::DataOutBase::VtkFlags flags;
  flags.time = time;
  data_out.set_flags(flags);
  OutputFile vtu(vtu_file);
  try
  {
    data_out.write_vtu(vtu);
  }
  catch (const dealii::ExceptionBase&)
  {
    vtu.close(); // names the file and the reason of a failed write
    throw;
  }
  vtu.close();
}

void write_stitch_wire_profiles(const CatenaryDiscretisation& d,
                                const SemiDiscreteSystem& system,
                                const dealii::Vector<double>& q,
                                const std::string& csv_file)
{
  const StitchWireSpace& stitch = d.stitch_wires();
  const CatenaryParameters& c = d.catenary_parameters();
  if (stitch.n_wires() == 0)
    return;
  OutputFile csv(csv_file);
  csv << "stitch_wire,support,x_m,w_stitch_wire_m,w_carrier_m\n" << std::setprecision(12);
  for (unsigned int i = 0; i < stitch.n_wires(); ++i)
    for (unsigned int k = 0; k <= stitch.n_elements(i); ++k)
    {
      const double x = stitch.node_position(i, k);
      csv << i + 1 << ',' << c.stitch_wires[i].support << ',' << x << ','
          << c.support_height + stitch_wire_point_row(d, system, i, x).dot(q) << ','
          << c.support_height + wire_point_row(d, system, Wire::carrier, x).dot(q)
          << '\n';
    }
  csv.close();
}
} // namespace pantocat
