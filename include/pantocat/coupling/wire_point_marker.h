#pragma once

#include <pantocat/base/contact_point_motion.h>
#include <pantocat/lac/sparse_row.h>
#include <pantocat/space/catenary_discretisation.h>

namespace pantocat
{
/**
 * The catenary's side of a coupling: a point x(t) moving along the contact
 * wire, as rows in the numbering of the semi-discrete system,
 *
 *   F_w(t) q = w_w(x(t), t) weighted by the load shape,   Eq. (33),
 *   dF_w/dt = -x' r_1,   d2F_w/dt2 = x'^2 r_2 - x'' r_1,
 *
 * with r_k the load rows of the space discretisation (Sec. 4.1). It knows the
 * wire only through CatenaryDiscretisation::load_row(), and nothing of what
 * is attached at the point (a pantograph's head, a prescribed force).
 *
 * The motion is along the line; a section of a line sees it from its start.
 * Where the load does not touch the section's domain the rows are empty:
 * beyond its anchors a section's contact wire is out of reach.
 */
class WirePointMarker
{
public:
  WirePointMarker(const CatenaryDiscretisation& discretisation, unsigned int wire_offset,
                  const ContactPointMotion& motion);

  /// F_w(t) into @p row (global numbering).
  void row(double t, SparseRow& row) const;

  /**
   * F_w(t) into @p row and, for @p max_order >= 1, dF_w/dt into @p first,
   * for max_order >= 2 also d2F_w/dt2 into @p second: one call for the load
   * rows.
   */
  void rows(double t, SparseRow& row, SparseRow& first, SparseRow& second,
            unsigned int max_order) const;

  /**
   * The height of the wire's reference (the support chord) at the point,
   * weighted by the load shape (CatenaryDiscretisation::reference_height()),
   * and its time derivatives up to @p max_order: what F_w q adds to it is the
   * wire's height at the point.
   */
  void reference_heights(double t, unsigned int max_order, double& z, double& z_t,
                         double& z_tt) const;
  const ContactPointMotion& motion() const { return motion_; }

private:
  /// x(t) in the section's coordinate (the motion is along the line).
  double local_position(double t) const;
  /// True while the load at @p x touches the section's domain.
  bool within_reach(double x) const;

  const CatenaryDiscretisation& discretisation;
  unsigned int wire_offset;
  ContactPointMotion motion_;
};
} // namespace pantocat
