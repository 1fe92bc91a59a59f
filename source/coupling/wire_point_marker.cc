#include <pantocat/coupling/wire_point_marker.h>

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

void WirePointMarker::time_derivatives(const double t, SparseRow& first,
                                       SparseRow& second,
                                       const bool second_derivative) const
{
  const double x = motion_.position(t), xd = motion_.velocity(t),
               xdd = motion_.acceleration(t);
  discretisation.load_row(x, 1, first);
  if (second_derivative)
  {
    // x'^2 r_2 - x'' r_1 (r_1 and r_2 share their pattern).
    discretisation.load_row(x, 2, second);
    for (std::size_t k = 0; k < second.size(); ++k)
      second.value[k] = xd * xd * second.value[k] - xdd * first.value[k];
    second.shift(wire_offset);
  }
  for (double& value : first.value)
    value *= -xd;
  first.shift(wire_offset);
}
} // namespace pantocat
