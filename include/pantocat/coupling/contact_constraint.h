#pragma once

#include <pantocat/coupling/wire_point_marker.h>
#include <pantocat/system/constraint.h>

#include <string>

namespace pantocat
{
/**
 * Where a pantograph meets the catenary, and nowhere else: the contact
 * constraint of Eqs. (26) and (32),
 *
 *   Delta_p(t) = F_w(t) q_w - b(t, q_MBS) >= 0,
 *
 * with G(t) = [F_w(t), -B] and its time derivatives for the hidden
 * constraints (Sec. 4.1): G_t = [dF_w/dt, 0], G_tt = [d2F_w/dt2, 0]. The
 * catenary's side is a WirePointMarker (rows of the wire at the moving point),
 * the pantograph's side its head row B in global numbering; neither knows
 * the other.
 */
class ContactConstraint : public Constraint
{
public:
  /// @p head is B of the pantograph, already in global numbering; a
  /// @p compliance with k > 0 makes it penalty contact (Constraint).
  ContactConstraint(std::string name, WirePointMarker wire, const SparseRow& head,
                    Kind kind, Compliance compliance = {});

  bool depends_on_time() const override { return true; }
  void evaluate(double t, ConstraintState& state,
                unsigned int max_order = 2) const override;

  const ContactPointMotion& motion() const { return wire.motion(); }

private:
  WirePointMarker wire;
  SparseRow minus_head; ///< -B in global numbering
};
} // namespace pantocat
