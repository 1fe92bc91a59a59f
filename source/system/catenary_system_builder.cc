#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>
#include <pantocat/system/catenary_system_builder.h>

namespace pantocat
{
namespace
{
void check_dropper_rows(const CatenaryDiscretisation& d,
                        const std::vector<SparseRow>& rows)
{
  const auto& x = d.catenary_parameters().dropper_positions;
  const std::string parameter = "Discretisation/Number of intervals";
  for (unsigned int j = 0; j < rows.size(); ++j)
  {
    require(rows[j].size() > 0, parameter, d.n_intervals(),
            "grid too coarse: dropper " + std::to_string(j + 1) +
                " at x = " + number_to_string(x[j]) + " m falls on a boundary node");
    for (unsigned int i = 0; i < j; ++i)
      require(rows[i].index != rows[j].index || rows[i].value != rows[j].value, parameter,
              d.n_intervals(),
              "grid too coarse: droppers " + std::to_string(i + 1) + " and " +
                  std::to_string(j + 1) + " fall on the same node");
  }
}
} // namespace

SparseRow dropper_row(const CatenaryDiscretisation& d, const SemiDiscreteSystem& system,
                      const unsigned int j)
{
  const double x = d.catenary_parameters().dropper_positions[j];
  SparseRow carrier = d.point_row(Wire::carrier, x);
  SparseRow wire = d.point_row(Wire::contact_wire, x);
  carrier.shift(system.block("carrier").first);
  wire.shift(system.block("contact wire").first);
  SparseRow row = wire;
  for (std::size_t k = 0; k < carrier.size(); ++k)
    row.add(carrier.index[k], -carrier.value[k]);
  return row;
}

SemiDiscreteSystem build_catenary_system(const CatenaryDiscretisation& d,
                                         const Constraint::Kind dropper_kind,
                                         const std::vector<const BlockOperator*>& extra)
{
  const CatenaryParameters& p = d.catenary_parameters();
  BlockOperator carrier, wire;
  d.assemble(Wire::carrier, carrier);
  d.assemble(Wire::contact_wire, wire);

  std::vector<SparseRow> wire_rows;
  for (unsigned int j = 0; j < p.n_droppers(); ++j)
  {
    // Clamp and half-dropper weights act on both wires, Eq. (4).
    const double x = p.dropper_positions[j];
    d.point_row(Wire::carrier, x).add_transpose_to(carrier.load, -p.clamp_load(j));
    wire_rows.push_back(d.point_row(Wire::contact_wire, x));
    wire_rows.back().add_transpose_to(wire.load, -p.clamp_load(j));
  }
  check_dropper_rows(d, wire_rows);

  std::vector<const BlockOperator*> bodies = {&carrier, &wire};
  bodies.insert(bodies.end(), extra.begin(), extra.end());
  SemiDiscreteSystem system;
  system.set_blocks(bodies);
  for (unsigned int j = 0; j < p.n_droppers(); ++j)
    system.add_constraint(std::make_unique<FixedConstraint>(
        "dropper " + std::to_string(j + 1), dropper_kind, dropper_row(d, system, j),
        p.dropper_lengths[j] - p.support_height));
  return system;
}
} // namespace pantocat
