#pragma once

#include <pantocat/pantograph/pantograph_model.h>
#include <pantocat/space/catenary_discretisation.h>
#include <pantocat/system/constraint.h>

namespace pantocat
{
/// The motion of the contact point along the track, x_p(t) = x_{p,0} + v_p t (Sec. 2.2).
struct ContactPointMotion
{
  double initial_position = 2.;
  double speed = 32.;

  double position(double t) const { return initial_position + speed * t; }
  double velocity(double) const { return speed; }
  double acceleration(double) const { return 0.; }
};

/**
 * The coupling of catenary and pantograph, Eqs. (26) and (32):
 *
 *   Delta_p(t) = F_w(t) q_w - b(t, q_MBS) >= 0,   F_w(t) from (33),
 *
 * with G(t) = [F_w(t), -B] and its time derivatives for the hidden
 * constraints (Sec. 4.1): G_t = [-x_p' r_1, 0], G_tt = [x_p'^2 r_2 - x_p'' r_1, 0],
 * where r_k are the load rows of the space discretisation. The constraint knows
 * the catenary only through those rows and the pantograph only through B.
 */
class ContactConstraint : public Constraint
{
public:
  ContactConstraint(const CatenaryDiscretisation& discretisation,
                    const PantographModel& pantograph, unsigned int wire_offset,
                    unsigned int pantograph_offset, ContactPointMotion motion, Kind kind);

  bool depends_on_time() const override { return true; }
  void evaluate(double t, ConstraintState& state,
                unsigned int max_order = 2) const override;

  const ContactPointMotion& motion() const { return motion_; }

private:
  const CatenaryDiscretisation& discretisation;
  SparseRow head; ///< -B in global numbering
  unsigned int wire_offset;
  ContactPointMotion motion_;
};
} // namespace pantocat
