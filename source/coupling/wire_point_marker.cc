#include <pantocat/coupling/wire_point_marker.h>

#include <algorithm>

namespace pantocat
{
WirePointMarker::WirePointMarker(const CatenaryDiscretisation& discretisation,
                                 const unsigned int wire_offset,
                                 const ContactPointMotion& motion)
    : discretisation(discretisation), wire_offset(wire_offset), motion_(motion)
{
}

double WirePointMarker::local_position(const double t) const
{
  return motion_.position(t) - discretisation.catenary_parameters().start;
}

bool WirePointMarker::within_reach(const double x) const
{
  const double eps =
      discretisation.discretisation_parameters().load_shape == LoadShape::point
          ? 0.
          : discretisation.smoothed_delta().epsilon();
  return x >= -eps && x <= discretisation.catenary_parameters().length() + eps;
}

void WirePointMarker::row(const double t, SparseRow& r) const
{
  const double x = local_position(t);
  if (!within_reach(x))
  {
    r.clear();
    return;
  }
  discretisation.load_row(x, 0, r);
  r.shift(wire_offset);
}

void WirePointMarker::rows(const double t, SparseRow& row, SparseRow& first,
                           SparseRow& second, const unsigned int max_order) const
{
  const double x = local_position(t);
  if (!within_reach(x))
  {
    row.clear(), first.clear(), second.clear();
    return;
  }
  SparseRow* const load[3] = {&row, &first, &second};
  discretisation.load_rows(x, 0, std::min(max_order, 2u) + 1, load);
  row.shift(wire_offset);
  if (max_order == 0)
    return;
  const double xd = motion_.velocity(t), xdd = motion_.acceleration(t);
  if (max_order >= 2)
  {
    // x'^2 r_2 - x'' r_1 (r_1 and r_2 share their pattern).
    for (std::size_t k = 0; k < second.size(); ++k)
      second.value[k] = xd * xd * second.value[k] - xdd * first.value[k];
    second.shift(wire_offset);
  }
  for (double& value : first.value)
    value *= -xd;
  first.shift(wire_offset);
}

void WirePointMarker::reference_heights(const double t, const unsigned int max_order,
                                        double& z, double& z_t, double& z_tt) const
{
  const double x = local_position(t);
  z = discretisation.reference_height(x, 0);
  if (max_order == 0)
    return;
  const double xd = motion_.velocity(t), slope = discretisation.reference_height(x, 1);
  z_t = slope * xd;
  if (max_order >= 2)
    z_tt =
        discretisation.reference_height(x, 2) * xd * xd + slope * motion_.acceleration(t);
}
} // namespace pantocat
