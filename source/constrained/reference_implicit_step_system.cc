#include <pantocat/base/input_error.h>
#include <pantocat/constrained/reference_implicit_step_system.h>

#include <deal.II/lac/lapack_full_matrix.h>

#include <array>
#include <cmath>
#include <sstream>

namespace pantocat
{
namespace
{
using Levels = std::array<double, 3>;
constexpr unsigned int lambda_kind = 0, eta_kind = 1, mu_kind = 2;
constexpr unsigned int force_law_kind = 3; ///< the equation of an engaged spring

ConstrainedOperator::Definition operator_of(const double mass, const double damping,
                                            const double stiffness, const char* what)
{
  ConstrainedOperator::Definition d;
  d.mass = mass;
  d.damping = damping;
  d.stiffness = stiffness;
  d.what = what;
  return d;
}

/// g, dg/dt, d2g/dt2 of row @p r on q, v, a (without its offsets z).
Levels levels(const ConstraintState& r, const ReferenceImplicitStepSystem::Response& x)
{
  return {{r.G.dot(x.q), r.G_t.dot(x.q) + r.G.dot(x.v),
           r.G_tt.dot(x.q) + 2. * r.G_t.dot(x.v) + r.G.dot(x.a)}};
}

/// Equation @p kind (a level, or force_law_kind) of constraint @p c on @p L.
double equation(const Constraint& c, const unsigned int kind, const Levels& L)
{
  if (kind != force_law_kind)
    return L[kind];
  return L[0] + c.compliance().damping / c.compliance().stiffness * L[1];
}

} // namespace

ReferenceImplicitStepSystem::ReferenceImplicitStepSystem(const SemiDiscreteSystem& system,
                                                         const double c)
    : ImplicitStepSystem(system, c),
      S(system, operator_of(c * c, c, 1., "BDF iteration matrix K + c D + c^2 M")),
      M(system, operator_of(1., 0., 0., "mass matrix M"))
{
}

void ReferenceImplicitStepSystem::start(const std::vector<ConstraintState>& r,
                                        const double t, const dealii::Vector<double>& rq,
                                        const dealii::Vector<double>& rv,
                                        const std::vector<bool>* /*held*/,
                                        const NextHistory* n, const bool /*continued*/)
{
  keep_step(r, t, rq, rv, n);
  // The base solution: S q = f + M (rho_v + c rho_q) + D rho_q, v = c q - rho_q,
  // a = c v - rho_v.
  dealii::Vector<double> h(rv);
  h.add(c, rq);
  S.solve_history(t, h, rq, base.q);
  base.v = base.q;
  base.v.sadd(c, -1., rq);
  base.a = base.v;
  base.a.sadd(c, -1., rv);
  for (auto it = responses.begin(); it != responses.end();)
    it = system.constraints[it->first.first]->depends_on_time() ? responses.erase(it)
                                                                : std::next(it);
}

const ReferenceImplicitStepSystem::Response&
ReferenceImplicitStepSystem::response(const unsigned int i, const unsigned int kind)
{
  const auto known = responses.find({i, kind});
  if (known != responses.end())
    return known->second;
  const unsigned int n = system.n_dofs();
  const ConstraintState& r = (*rows)[i];
  dealii::Vector<double> Y(n), Z(n), b(n), DU(n);
  r.G.add_transpose_to(Y, 1.);
  r.G_t.add_transpose_to(Z, 1.);
  M.apply_inverse(Y);
  M.apply_inverse(Z);
  Response x;
  x.q.reinit(n);
  if (kind == lambda_kind)
    r.G.add_transpose_to(x.q, 1.);
  else if (kind == eta_kind)
  {
    r.G.add_transpose_to(x.q, 1.);
    r.G_t.add_transpose_to(x.q, c);
    system.damping.vmult(DU, Z);
    x.q += DU;
  }
  else
  {
    r.G.add_transpose_to(x.q, c);
    system.damping.vmult(DU, Y);
    x.q += DU;
  }
  S.apply_inverse(x.q);
  x.v = x.q;
  x.v *= c;
  if (kind != lambda_kind)
    x.v.add(-1., kind == eta_kind ? Z : Y);
  x.a = x.v;
  x.a *= c;
  if (kind == eta_kind)
    x.a.add(-1., Y);
  return responses.emplace(std::make_pair(i, kind), std::move(x)).first->second;
}

dealii::Vector<double>
ReferenceImplicitStepSystem::multipliers(const std::vector<Slot>& unknowns,
                                         const std::vector<Slot>& equations)
{
  const unsigned int p = unknowns.size();
  dealii::Vector<double> y(p);
  if (p == 0)
    return y;
  // Each equation's levels of each response, and of the base with the rows' offsets.
  dealii::LAPACKFullMatrix<double> E(p, p);
  for (unsigned int e = 0; e < p; ++e)
  {
    const unsigned int i = equations[e].constraint;
    const Constraint& constraint = *system.constraints[i];
    const ConstraintState& r = (*rows)[i];
    for (unsigned int u = 0; u < p; ++u)
      E(e, u) = equation(constraint, equations[e].kind,
                         levels(r, response(unknowns[u].constraint, unknowns[u].kind)));
    if (equations[e].kind == force_law_kind)
      E(e, e) += 1. / constraint.compliance().stiffness;
    Levels L = levels(r, base);
    L[0] += r.z;
    L[1] += r.z_t;
    L[2] += r.z_tt;
    y(e) = -equation(constraint, equations[e].kind, L);
  }
  std::ostringstream singular;
  singular << "the active constraints are linearly dependent at t = " << time
           << " s (BDF step)";
  try
  {
    E.compute_lu_factorization();
  }
  catch (const std::exception&)
  {
    throw SimulationError(singular.str());
  }
  E.solve(y);
  for (unsigned int u = 0; u < p; ++u)
    if (!std::isfinite(y(u)))
      throw SimulationError(singular.str());
  return y;
}

void ReferenceImplicitStepSystem::solve(const std::vector<Role>& roles,
                                        dealii::Vector<double>& q,
                                        dealii::Vector<double>& v,
                                        dealii::Vector<double>& a,
                                        std::vector<double>& lambda)
{
  std::vector<Slot> unknowns, equations;
  for (unsigned int i = 0; i < roles.size(); ++i)
    if (roles[i] == Role::force)
      unknowns.insert(unknowns.end(), {{i, lambda_kind}, {i, eta_kind}, {i, mu_kind}}),
          equations.insert(equations.end(), {{i, 2}, {i, 0}, {i, 1}});
    else if (roles[i] == Role::touching)
      unknowns.insert(unknowns.end(), {{i, eta_kind}, {i, mu_kind}}),
          equations.insert(equations.end(), {{i, 0}, {i, 1}});
    else if (roles[i] == Role::engaged)
      unknowns.push_back({i, lambda_kind}), equations.push_back({i, force_law_kind});
  const dealii::Vector<double> y = multipliers(unknowns, equations);
  q = base.q;
  v = base.v;
  a = base.a;
  lambda.assign(roles.size(), 0.);
  for (unsigned int u = 0; u < unknowns.size(); ++u)
  {
    const Response& x = response(unknowns[u].constraint, unknowns[u].kind);
    q.add(y(u), x.q);
    v.add(y(u), x.v);
    a.add(y(u), x.a);
    if (unknowns[u].kind == lambda_kind)
      lambda[unknowns[u].constraint] = y(u);
  }
  if (with_next)
  {
    next_rho_q = q;
    next_rho_q.sadd(next_request.f, next_request.fp, *next_request.q_n);
    next_rho_v = v;
    next_rho_v.sadd(next_request.f, next_request.fp, *next_request.v_n);
  }
}

void ReferenceImplicitStepSystem::take_next_history(dealii::Vector<double>& rq,
                                                    dealii::Vector<double>& rv)
{
  rq.swap(next_rho_q);
  rv.swap(next_rho_v);
}
} // namespace pantocat
