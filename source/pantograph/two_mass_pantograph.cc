#include <pantocat/base/input_error.h>
#include <pantocat/pantograph/two_mass_pantograph.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>

namespace pantocat
{
TwoMassPantograph::TwoMassPantograph(const TwoMassPantographParameters& parameters)
    : p(parameters)
{
}

void TwoMassPantograph::assemble(BlockOperator& op) const
{
  op.name = "pantograph";
  dealii::DynamicSparsityPattern dsp(2, 2);
  for (unsigned int i = 0; i < 2; ++i)
    for (unsigned int j = 0; j < 2; ++j)
      dsp.add(i, j);
  op.sparsity->copy_from(dsp);
  op.reinit_matrices(2);
  op.mass_is_diagonal = true;
  // Without a frame spring only the contact holds the bodies (a static
  // equilibrium then needs the contact: the saddle-point way).
  op.stiffness_is_definite = p.head_stiffness > 0. && p.frame_stiffness > 0.;
  op.mass.set(0, 0, p.head_mass);
  op.mass.set(1, 1, p.frame_mass);
  op.mass.set(0, 1, 0.);
  op.mass.set(1, 0, 0.);
  // Eq. (12): the head-frame spring/damper couples the bodies, c_2/d_2 ground the frame.
  op.stiffness.set(0, 0, p.head_stiffness);
  op.stiffness.set(0, 1, -p.head_stiffness);
  op.stiffness.set(1, 0, -p.head_stiffness);
  op.stiffness.set(1, 1, p.head_stiffness + p.frame_stiffness);
  op.damping.set(0, 0, p.head_damping);
  op.damping.set(0, 1, -p.head_damping);
  op.damping.set(1, 0, -p.head_damping);
  op.damping.set(1, 1, p.head_damping + p.frame_damping);
  op.load(0) = 0.;
  op.load(1) = p.uplift_force;
}

SparseRow TwoMassPantograph::head_row() const
{
  SparseRow B;
  B.add(0, 1.);
  return B;
}

void TwoMassPantograph::consistent_state(const double head_position,
                                         const double head_velocity,
                                         const double head_acceleration,
                                         const double contact_force, const double offset,
                                         dealii::Vector<double>& q,
                                         dealii::Vector<double>& v) const
{
  require(p.head_damping > 0., "Pantograph/Two-mass model/Head damping", p.head_damping,
          "must be > 0: the consistent initial state of Sec. 2.2 solves the head "
          "equation of (12) for the frame velocity");
  q.reinit(2);
  v.reinit(2);
  q(0) = head_position;
  q(1) = head_position - offset;
  v(0) = head_velocity;
  v(1) = head_velocity +
         (p.head_mass * head_acceleration + p.head_stiffness * offset + contact_force) /
             p.head_damping;
}
} // namespace pantocat
