#pragma once

#include <pantocat/base/contact_point_motion.h>
#include <pantocat/space/catenary_discretisation.h>
#include <pantocat/lac/sparse_row.h>

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

  const ContactPointMotion& motion() const { return motion_; }

private:
  const CatenaryDiscretisation& discretisation;
  unsigned int wire_offset;
  ContactPointMotion motion_;
};
} // namespace pantocat
