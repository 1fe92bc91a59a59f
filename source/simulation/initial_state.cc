#include <pantocat/analysis/static_equilibrium.h>
#include <pantocat/base/input_error.h>
#include <pantocat/simulation/initial_state.h>
#include <pantocat/time/mass_inverse.h>

namespace pantocat
{
DynamicState consistent_initial_state(const SemiDiscreteSystem& catenary_only,
                                      const SemiDiscreteSystem& coupled,
                                      const PantographModel& pantograph,
                                      const ContactConstraint& contact,
                                      const double contact_force, const double offset)
{
  const unsigned int n = coupled.n_dofs(), m = coupled.n_constraints();
  const unsigned int contact_index = m - 1;
  ConstraintState rows;
  contact.evaluate(0., rows);

  // 1. The catenary at rest under lambda_p(0): the wire part of G is F_w(0).
  dealii::Vector<double> contact_load(catenary_only.n_dofs());
  for (std::size_t k = 0; k < rows.G.size(); ++k)
    if (rows.G.index[k] < catenary_only.n_dofs())
      contact_load(rows.G.index[k]) += contact_force * rows.G.value[k];
  const StaticEquilibrium rest = solve_static_equilibrium(catenary_only, contact_load);

  DynamicState s;
  s.t = 0.;
  s.q.reinit(n);
  s.v.reinit(n);
  s.a.reinit(n);
  for (unsigned int i = 0; i < catenary_only.n_dofs(); ++i)
    s.q(i) = rest.q(i);

  // 2. Head position, velocity and acceleration from g = 0, dg/dt = 0,
  //    d2g/dt2 = 0 with the catenary at rest: B x_MBS = (wire part of the rows) q.
  const double head_position = rows.G.dot(s.q); // pantograph entries of q are still 0
  const double head_velocity = rows.G_t.dot(s.q);
  const double head_acceleration = rows.G_tt.dot(s.q);

  // 3. The pantograph's own equations complete its state.
  dealii::Vector<double> q_mbs, v_mbs;
  pantograph.consistent_state(head_position, head_velocity, head_acceleration,
                              contact_force, offset, q_mbs, v_mbs);
  const DofBlock& block = coupled.block("pantograph");
  for (unsigned int i = 0; i < block.size; ++i)
  {
    s.q(block.first + i) = q_mbs(i);
    s.v(block.first + i) = v_mbs(i);
  }

  // 4. Multipliers and accelerations of the whole system.
  s.lambda.assign(m, 0.);
  s.active.assign(m, true);
  for (unsigned int i = 0; i < rest.multipliers.size(); ++i)
  {
    s.lambda[i] = rest.multipliers[i];
    s.active[i] = rest.active[i];
  }
  s.lambda[contact_index] = contact_force;
  dealii::Vector<double> force(coupled.load), tmp(n);
  coupled.stiffness.vmult(tmp, s.q);
  force -= tmp;
  coupled.damping.vmult(tmp, s.v);
  force -= tmp;
  std::vector<ConstraintState> states(m);
  for (unsigned int i = 0; i < m; ++i)
  {
    coupled.constraints[i]->evaluate(0., states[i]);
    states[i].G.add_transpose_to(force, s.lambda[i]);
  }
  MassInverse mass_inverse;
  mass_inverse.initialize(coupled.mass, coupled.mass_is_diagonal, "mass matrix M");
  s.a = force;
  mass_inverse.apply(s.a);
  return s;
}
} // namespace pantocat
