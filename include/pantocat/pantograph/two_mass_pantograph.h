#pragma once

#include <pantocat/pantograph/pantograph_model.h>
#include <pantocat/pantograph/pantograph_parameters.h>

namespace pantocat
{
/**
 * The two-mass pantograph of Eq. (12): head (body 1) and frame (body 2),
 * springs c_1 (head-frame) and c_2 (frame-ground), dampers d_1 and d_2, and
 * the static force F_0 on the frame; q_MBS = (w_p1, w_p2), b = w_p1.
 */
class TwoMassPantograph : public PantographModel
{
public:
  explicit TwoMassPantograph(const TwoMassPantographParameters& parameters);

  std::string name() const override { return "two-mass"; }
  unsigned int n_dofs() const override { return 2; }
  std::vector<std::string> coordinate_names() const override { return {"w_p1", "w_p2"}; }
  void assemble(BlockOperator& op) const override;
  SparseRow head_row() const override;
  double static_force() const override { return p.uplift_force; }

  /**
   * Sec. 2.2: w_p1 = head position, w_p2 = w_p1 - offset (13); the head
   * velocity is given by the hidden velocity constraint; the frame velocity
   * follows from the head equation of (12),
   *   m_1 a_1 = -d_1 (v_1 - v_2) - c_1 (w_1 - w_2) - lambda_p,
   * so that lambda_p(0) is consistent on acceleration level (needs d_1 > 0).
   */
  void consistent_state(double head_position, double head_velocity,
                        double head_acceleration, double contact_force, double offset,
                        dealii::Vector<double>& q,
                        dealii::Vector<double>& v) const override;

private:
  TwoMassPantographParameters p;
};
} // namespace pantocat
