#pragma once

#include <pantocat/pantograph/pantograph_model.h>
#include <pantocat/pantograph/pantograph_parameters.h>

namespace pantocat
{
/**
 * A three-mass pantograph: head (body 1), upper frame (body 2) and lower
 * frame (body 3) in a chain, each linked to the next by a spring c_i and a
 * damper d_i, the lower frame to the ground by c_3, d_3, and the static force
 * F_0 on the lower frame:
 *
 *   m_1 w_1'' = -c_1 (w_1 - w_2) - d_1 (w_1' - w_2') - lambda_p,
 *   m_2 w_2'' =  c_1 (w_1 - w_2) + d_1 (w_1' - w_2') - c_2 (w_2 - w_3) - d_2 (...),
 *   m_3 w_3'' =  c_2 (w_2 - w_3) + d_2 (w_2' - w_3') - c_3 w_3 - d_3 w_3' + F_0,
 *
 * the form (10) with b = w_1 as in (11). It attaches through the same
 * coupling layer as the two-mass model (12).
 */
class ThreeMassPantograph : public PantographModel
{
public:
  explicit ThreeMassPantograph(const ThreeMassPantographParameters& parameters);

  std::string name() const override { return "three-mass"; }
  unsigned int n_dofs() const override { return 3; }
  std::vector<std::string> coordinate_names() const override
  {
    return {"w_p1", "w_p2", "w_p3"};
  }
  void assemble(BlockOperator& op) const override;
  SparseRow head_row() const override;
  double static_force() const override { return p.uplift_force; }

  /**
   * As for the two-mass model: w_1 = head position, w_2 = w_1 - offset, the
   * velocity of body 2 from the head equation (consistent lambda_p(0), needs
   * d_1 > 0); body 3 at rest relative to the head, where its own forces
   * balance statically: c_2 (w_2 - w_3) - c_3 w_3 + F_0 = 0.
   */
  void consistent_state(double head_position, double head_velocity,
                        double head_acceleration, double contact_force, double offset,
                        dealii::Vector<double>& q,
                        dealii::Vector<double>& v) const override;

private:
  ThreeMassPantographParameters p;
};
} // namespace pantocat
