#include <pantocat/coupling/contact_constraint.h>

namespace pantocat
{
ContactConstraint::ContactConstraint(const CatenaryDiscretisation& discretisation,
                                     const PantographModel& pantograph,
                                     const unsigned int wire_offset,
                                     const unsigned int pantograph_offset,
                                     const ContactPointMotion motion, const Kind kind)
    : Constraint("contact", kind), discretisation(discretisation),
      head(pantograph.head_row()), wire_offset(wire_offset), motion_(motion)
{
  head.shift(pantograph_offset);
  for (double& b : head.value)
    b = -b;
}

void ContactConstraint::evaluate(const double t, ConstraintState& s,
                                 const unsigned int max_order) const
{
  const double x = motion_.position(t), xd = motion_.velocity(t),
               xdd = motion_.acceleration(t);
  discretisation.load_row(x, 0, s.G);
  s.G.shift(wire_offset);
  for (std::size_t k = 0; k < head.size(); ++k)
    s.G.add(head.index[k], head.value[k]);

  s.z = s.z_t = s.z_tt = 0.;
  if (max_order == 0)
    return;
  discretisation.load_row(x, 1, s.G_t);
  if (max_order >= 2)
  {
    // G_tt = x'^2 r_2 - x'' r_1 (r_1 and r_2 share their pattern).
    discretisation.load_row(x, 2, s.G_tt);
    for (std::size_t k = 0; k < s.G_tt.size(); ++k)
      s.G_tt.value[k] = xd * xd * s.G_tt.value[k] - xdd * s.G_t.value[k];
    s.G_tt.shift(wire_offset);
  }
  for (double& value : s.G_t.value)
    value *= -xd;
  s.G_t.shift(wire_offset);
}
} // namespace pantocat
