#pragma once

#include <pantocat/lac/sparse_row.h>
#include <pantocat/system/block_operator.h>

#include <deal.II/lac/vector.h>

#include <string>

namespace pantocat
{
/**
 * A lumped-mass pantograph, Eq. (10): M_MBS q'' + D q' + K q = f + (forces of
 * the constraints), seen by the catenary only through the vertical position
 * of its head
 *
 *   b(t, q_MBS) = B q_MBS + b_0(t),   B = db/dq_MBS,   Eq. (11).
 *
 * The coupling layer (ContactConstraint) asks nothing else, so any lumped
 * model that provides these attaches without changes to the catenary or to
 * the integrators.
 */
class PantographModel
{
public:
  virtual ~PantographModel() = default;

  virtual std::string name() const = 0;
  virtual unsigned int n_dofs() const = 0;
  /// Names of the coordinates q_MBS, for outputs ("w_p1", "w_p2", ...).
  virtual std::vector<std::string> coordinate_names() const = 0;

  /// Mass, damping, stiffness and the constant applied force of (10).
  virtual void assemble(BlockOperator& op) const = 0;

  /// The static force F_0 that presses the pantograph upwards [N]: the scale of its
  /// contact force (guards measure forces against it).
  virtual double static_force() const = 0;

  /// B = db/dq_MBS (local numbering of q_MBS).
  virtual SparseRow head_row() const = 0;

  /**
   * A state with the head at @p head_position, velocity and acceleration, in
   * which (10) holds with the contact force @p contact_force and the given
   * relative offset of the bodies (Sec. 2.2 and 6). Writes q and v.
   */
  virtual void consistent_state(double head_position, double head_velocity,
                                double head_acceleration, double contact_force,
                                double offset, dealii::Vector<double>& q,
                                dealii::Vector<double>& v) const = 0;
};
} // namespace pantocat
