#include <pantocat/analysis/static_equilibrium.h>
#include <pantocat/base/input_error.h>
#include <pantocat/constrained_fast/mass_inverse.h>
#include <pantocat/simulation/initial_state.h>

#include <deal.II/base/numbers.h>

#include <cmath>

namespace pantocat
{
namespace
{
/// a = M^-1 (f(0) - K q - D v + sum_i G_i^T lambda_i): step 4 of Sec. 2.2.
void complete_accelerations(const SemiDiscreteSystem& system, DynamicState& s)
{
  const unsigned int n = system.n_dofs();
  dealii::Vector<double> force(n), tmp(n);
  system.load_at(0., force);
  system.stiffness.vmult(tmp, s.q);
  force -= tmp;
  system.damping.vmult(tmp, s.v);
  force -= tmp;
  ConstraintState rows;
  for (unsigned int i = 0; i < system.n_constraints(); ++i)
  {
    system.constraints[i]->evaluate(0., rows);
    rows.G.add_transpose_to(force, s.lambda[i]);
  }
  MassInverse mass_inverse;
  mass_inverse.initialize(system.mass, system.mass_is_diagonal, "mass matrix M");
  s.a = force;
  mass_inverse.apply(s.a);
}

DynamicState zero_state(const SemiDiscreteSystem& system)
{
  DynamicState s;
  s.t = 0.;
  s.q.reinit(system.n_dofs());
  s.v.reinit(system.n_dofs());
  s.a.reinit(system.n_dofs());
  s.lambda.assign(system.n_constraints(), 0.);
  s.active.assign(system.n_constraints(), true);
  return s;
}
} // namespace

StaticEquilibrium static_catenary(const SemiDiscreteSystem& catenary_only,
                                  const SemiDiscreteSystem& coupled,
                                  const std::vector<InitialContact>& contacts)
{
  const unsigned int n_catenary = catenary_only.n_dofs();
  // The time-dependent loads at t = 0 and every lambda_p(0) F_w(0)^T: the
  // wire part of each contact's G.
  dealii::Vector<double> f0(coupled.n_dofs()), extra(n_catenary);
  coupled.load_at(0., f0);
  for (unsigned int i = 0; i < n_catenary; ++i)
    extra(i) = f0(i) - coupled.load(i);
  ConstraintState rows;
  for (const InitialContact& c : contacts)
  {
    coupled.constraints[c.constraint]->evaluate(0., rows, 0);
    for (std::size_t k = 0; k < rows.G.size(); ++k)
      if (rows.G.index[k] < n_catenary)
        extra(rows.G.index[k]) += c.force * rows.G.value[k];
  }
  return solve_static_equilibrium(catenary_only, extra);
}

DynamicState consistent_initial_state(const SemiDiscreteSystem& catenary_only,
                                      const SemiDiscreteSystem& coupled,
                                      const std::vector<InitialContact>& contacts)
{
  const unsigned int n_catenary = catenary_only.n_dofs();
  // 1. The catenary at rest under its loads at t = 0 and every lambda_p(0).
  DynamicState s = zero_state(coupled);
  if (n_catenary > 0)
  {
    const StaticEquilibrium rest = static_catenary(catenary_only, coupled, contacts);
    for (unsigned int i = 0; i < n_catenary; ++i)
      s.q(i) = rest.q(i);
    for (unsigned int i = 0; i < rest.multipliers.size(); ++i)
    {
      s.lambda[i] = rest.multipliers[i];
      s.active[i] = rest.active[i];
    }
  }

  ConstraintState rows;
  for (const InitialContact& c : contacts)
  {
    // 2. Head position, velocity and acceleration from g = 0, dg/dt = 0,
    //    d2g/dt2 = 0 with the catenary at rest: B x_MBS = (wire part of the rows) q + z.
    coupled.constraints[c.constraint]->evaluate(0., rows);
    // A penalty contact carries lambda_p(0) as the penetration -g = lambda_p(0) / k_c.
    const Compliance& law = coupled.constraints[c.constraint]->compliance();
    const double penetration = law.stiffness > 0. ? c.force / law.stiffness : 0.;
    const double head_position =
        rows.G.dot(s.q) + rows.z + penetration; // pantograph entries still 0
    const double head_velocity = rows.G_t.dot(s.q) + rows.z_t;
    const double head_acceleration = rows.G_tt.dot(s.q) + rows.z_tt;

    // 3. The pantograph's own equations complete its state.
    dealii::Vector<double> q_mbs, v_mbs;
    c.model->consistent_state(head_position, head_velocity, head_acceleration, c.force,
                              c.offset, q_mbs, v_mbs);
    const DofBlock& block = coupled.block(c.block);
    for (unsigned int i = 0; i < block.size; ++i)
    {
      s.q(block.first + i) = q_mbs(i);
      s.v(block.first + i) = v_mbs(i);
    }
    s.lambda[c.constraint] = c.force;
  }

  // 4. Accelerations of the whole system.
  complete_accelerations(coupled, s);
  return s;
}

DynamicState static_initial_state(const SemiDiscreteSystem& coupled,
                                  const std::vector<InitialContact>& contacts)
{
  // 1. Everything at rest under its loads at t = 0: K q = f(0) + G^T lambda
  //    with every constraint, the contacts included.
  dealii::Vector<double> f0(coupled.n_dofs());
  coupled.load_at(0., f0);
  f0 -= coupled.load;
  const StaticEquilibrium rest = solve_static_equilibrium(coupled, f0);
  DynamicState s = zero_state(coupled);
  s.q = rest.q;
  for (unsigned int i = 0; i < coupled.n_constraints(); ++i)
  {
    s.lambda[i] = rest.multipliers[i];
    s.active[i] = rest.active[i];
  }
  // 2. Each pantograph moves as one body with its head, which follows the
  //    wire under the moving contact point: B v_MBS = G_t q + z_t.
  ConstraintState rows;
  for (const InitialContact& c : contacts)
  {
    coupled.constraints[c.constraint]->evaluate(0., rows);
    const DofBlock& block = coupled.block(c.block);
    const SparseRow head = c.model->head_row();
    double head_weight = 0.; // B 1: the head's rise per unit rise of the whole body
    for (std::size_t k = 0; k < head.size(); ++k)
      head_weight += head.value[k];
    const double speed = (rows.G_t.dot(s.q) + rows.z_t) / head_weight;
    for (unsigned int i = 0; i < block.size; ++i)
      s.v(block.first + i) = speed;
  }
  // 3. Accelerations of the whole system.
  complete_accelerations(coupled, s);
  return s;
}

DynamicState shaped_initial_state(const SemiDiscreteSystem& system,
                                  const CatenaryDiscretisation& space,
                                  const SceneParameters& scene)
{
  DynamicState s = zero_state(system);
  if (scene.initial_shape == InitialShape::sine_mode)
  {
    const double k = scene.initial_mode * M_PI / space.catenary_parameters().length();
    const double A = scene.initial_amplitude;
    dealii::Vector<double> q_w;
    space.interpolate(
        Wire::contact_wire, [&](const double x) { return A * std::sin(k * x); },
        [&](const double x) { return A * k * std::cos(k * x); }, q_w);
    const DofBlock& block = system.block("contact wire");
    for (unsigned int i = 0; i < block.size; ++i)
      s.q(block.first + i) = q_w(i);
  }
  complete_accelerations(system, s);
  return s;
}
} // namespace pantocat
