#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>
#include <pantocat/scene/droppers.h>

#include <algorithm>
#include <tuple>

namespace pantocat
{
namespace
{
/**
 * A dropper must sit on a free node, and no two on the same one (FDM, coarse
 * grids): the rows sorted, equal ones are neighbours (O(n log n)). Names the
 * pair that a check of every pair in order would name first.
 */
void check_dropper_rows(const SceneAssembly& a, const std::vector<SparseRow>& rows)
{
  const auto& x = a.catenary().dropper_positions;
  const std::string parameter = "Discretisation/Number of intervals";
  const unsigned int n = a.space().n_intervals();
  std::vector<unsigned int> order(rows.size());
  for (unsigned int j = 0; j < rows.size(); ++j)
    order[j] = j;
  const auto key = [&rows](const unsigned int j)
  { return std::tie(rows[j].index, rows[j].value); };
  std::stable_sort(order.begin(), order.end(),
                   [&](const unsigned int i, const unsigned int j)
                   { return key(i) < key(j); });
  // In a run of equal rows the first two are the run's smallest dropper numbers.
  unsigned int first = 0, second = rows.size();
  for (unsigned int k = 1; k < order.size(); ++k)
    if (key(order[k]) == key(order[k - 1]) &&
        (k < 2 || key(order[k - 2]) != key(order[k])) && order[k] < second)
      first = order[k - 1], second = order[k];
  unsigned int boundary = 0;
  while (boundary < rows.size() && rows[boundary].size() > 0)
    ++boundary;
  if (boundary < rows.size() && boundary <= second)
    require(false, parameter, n,
            "grid too coarse: dropper " + std::to_string(boundary + 1) + " at x = " +
                number_to_string(x[boundary]) + " m falls on a boundary node");
  if (second < rows.size())
    require(false, parameter, n,
            "grid too coarse: droppers " + std::to_string(first + 1) + " and " +
                std::to_string(second + 1) + " fall on the same node");
}

} // namespace

std::string Droppers::name() const
{
  return "droppers";
}

bool Droppers::enabled(const SceneParameters& scene, const CatenaryParameters&) const
{
  return scene.has_droppers();
}

void Droppers::add_constraints(SceneAssembly& a) const
{
  const CatenaryParameters& p = a.catenary();
  // The rows of the elastic wire whose grid holds the dropper (the contact
  // wire's, unless it is rigid).
  const Wire checked =
      a.scene.contact_wire == WireModel::elastic ? Wire::contact_wire : Wire::carrier;
  std::vector<SparseRow> rows;
  for (unsigned int j = 0; j < p.n_droppers(); ++j)
    rows.push_back(a.space().point_row(checked, p.dropper_positions[j]));
  check_dropper_rows(a, rows);

  const Constraint::Kind kind = a.scene.droppers == DropperModel::bilateral
                                    ? Constraint::Kind::bilateral
                                    : Constraint::Kind::unilateral;
  // An elastic dropper is the compliant unilateral constraint
  // g + lambda / k_d >= 0, lambda >= 0: force k_d max(-g, 0), the stretch
  // -g = (w_c + l_c - w_w) - l_j beyond the unstretched length l_j.
  const Compliance compliance{
      a.scene.droppers == DropperModel::elastic ? p.dropper_stiffness : 0., 0.};
  for (unsigned int j = 0; j < p.n_droppers(); ++j)
  {
    // Delta = H_w q_w - H_c q_c + (l_j - l_c), with u_c = w_c - l_c, Eq. (31);
    // in a stitched catenary H_c is the stitch wire's row where the dropper
    // hangs from it.
    const double x = p.dropper_positions[j];
    SparseRow row = a.wire_row(Wire::contact_wire, x);
    const SparseRow carrier = a.dropper_upper_row(j);
    for (std::size_t k = 0; k < carrier.size(); ++k)
      row.add(carrier.index[k], -carrier.value[k]);
    a.dropper_indices.push_back(a.system.n_constraints());
    a.system.add_constraint(std::make_unique<FixedConstraint>(
        a.constraint_name("dropper " + std::to_string(j + 1)), kind, row,
        p.dropper_lengths[j] - p.support_height, compliance));
  }
}

std::string Droppers::describe(const SceneAssembly& a) const
{
  const std::string model = a.scene.droppers == DropperModel::bilateral ? "bilateral (4)"
                            : a.scene.droppers == DropperModel::elastic
                                ? "elastic, tension only, k_d = " +
                                      number_to_string(a.catenary().dropper_stiffness) +
                                      " N/m"
                                : "unilateral (Sec. 5.3)";
  return std::to_string(a.catenary().n_droppers()) + " droppers, " + model;
}
} // namespace pantocat
