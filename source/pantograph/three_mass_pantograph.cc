#include <pantocat/base/input_error.h>
#include <pantocat/pantograph/three_mass_pantograph.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <algorithm>

namespace pantocat
{
ThreeMassPantograph::ThreeMassPantograph(const ThreeMassPantographParameters& parameters)
    : p(parameters)
{
}

void ThreeMassPantograph::assemble(BlockOperator& op) const
{
  op.name = "pantograph";
  dealii::DynamicSparsityPattern dsp(3, 3);
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = (i > 0 ? i - 1 : 0); j <= std::min(2u, i + 1); ++j)
      dsp.add(i, j);
  op.sparsity->copy_from(dsp);
  op.reinit_matrices(3);
  op.mass_is_diagonal = true;
  // Without every spring only the contact holds the bodies.
  op.stiffness_is_definite = std::all_of(p.stiffnesses.begin(), p.stiffnesses.end(),
                                         [](double k) { return k > 0.; });
  const double m[3] = {p.masses[0], p.masses[1], p.masses[2]};
  for (unsigned int i = 0; i < 3; ++i)
    op.mass.set(i, i, m[i]);
  // Link i joins bodies i and i + 1 (i = 0, 1); link 2 joins body 3 to the ground.
  const auto link =
      [](dealii::SparseMatrix<double>& matrix, const unsigned int i, const double value)
  {
    matrix.add(i, i, value);
    matrix.add(i + 1, i + 1, value);
    matrix.add(i, i + 1, -value);
    matrix.add(i + 1, i, -value);
  };
  for (unsigned int i = 0; i < 2; ++i)
  {
    link(op.stiffness, i, p.stiffnesses[i]);
    link(op.damping, i, p.dampings[i]);
  }
  op.stiffness.add(2, 2, p.stiffnesses[2]);
  op.damping.add(2, 2, p.dampings[2]);
  op.load(2) = p.uplift_force;
}

SparseRow ThreeMassPantograph::head_row() const
{
  SparseRow B;
  B.add(0, 1.);
  return B;
}

void ThreeMassPantograph::consistent_state(const double head_position,
                                           const double head_velocity,
                                           const double head_acceleration,
                                           const double contact_force,
                                           const double offset, dealii::Vector<double>& q,
                                           dealii::Vector<double>& v) const
{
  require(p.dampings[0] > 0., "Pantograph/Three-mass model/Dampings", p.dampings[0],
          "the head damper d_1 must be > 0: the consistent initial state solves the "
          "head equation for the velocity of body 2");
  q.reinit(3);
  v.reinit(3);
  q(0) = head_position;
  q(1) = head_position - offset;
  q(2) =
      (p.uplift_force + p.stiffnesses[1] * q(1)) / (p.stiffnesses[1] + p.stiffnesses[2]);
  v(0) = head_velocity;
  v(1) = head_velocity +
         (p.masses[0] * head_acceleration + p.stiffnesses[0] * offset + contact_force) /
             p.dampings[0];
  v(2) = head_velocity;
}
} // namespace pantocat
