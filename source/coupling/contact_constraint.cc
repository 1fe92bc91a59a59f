#include <pantocat/coupling/contact_constraint.h>

namespace pantocat
{
ContactConstraint::ContactConstraint(std::string name, WirePointMarker wire,
                                     const SparseRow& head, const Kind kind,
                                     const Compliance compliance)
    : Constraint(std::move(name), kind, compliance), wire(std::move(wire)),
      minus_head(head)
{
  for (double& b : minus_head.value)
    b = -b;
}

void ContactConstraint::evaluate(const double t, ConstraintState& s,
                                 const unsigned int max_order) const
{
  wire.rows(t, s.G, s.G_t, s.G_tt, max_order);
  for (std::size_t k = 0; k < minus_head.size(); ++k)
    s.G.add(minus_head.index[k], minus_head.value[k]);
  s.z = s.z_t = s.z_tt = 0.;
  wire.reference_heights(t, max_order, s.z, s.z_t, s.z_tt);
}
} // namespace pantocat
