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

void WirePointMarker::row(const double t, SparseRow& r) const
{
  discretisation.load_row(motion_.position(t), 0, r);
  r.shift(wire_offset);
}

void WirePointMarker::rows(const double t, SparseRow& row, SparseRow& first,
                           SparseRow& second, const unsigned int max_order) const
{
  const double x = motion_.position(t);
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

} // namespace pantocat
