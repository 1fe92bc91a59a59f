#include <pantocat/analysis/half_explicit_step_map.h>
#include <pantocat/time/half_explicit_integrator.h>

#include <cmath>
#include <limits>
#include <random>

namespace pantocat
{
namespace
{
/**
 * A constraint of the homogeneous view: the rows of @p original (at
 * @p frozen_time if frozen) without the offsets, bilateral.
 */
class HomogeneousConstraint : public Constraint
{
public:
  HomogeneousConstraint(const Constraint& original, const bool frozen,
                        const double frozen_time)
      : Constraint(original.name(), Kind::bilateral, original.compliance()),
        original(original), frozen(frozen), frozen_time(frozen_time)
  {
  }
  bool depends_on_time() const override { return original.depends_on_time(); }
  void evaluate(const double t, ConstraintState& state,
                const unsigned int max_order) const override
  {
    original.evaluate(frozen ? frozen_time : t, state, max_order);
    state.z = state.z_t = state.z_tt = 0.;
  }

private:
  const Constraint& original;
  const bool frozen;
  const double frozen_time;
};
} // namespace

std::unique_ptr<SemiDiscreteSystem> homogeneous_view(const SemiDiscreteSystem& system,
                                                     const std::vector<bool>& active,
                                                     const bool freeze,
                                                     const double frozen_time)
{
  auto view = std::make_unique<SemiDiscreteSystem>();
  view->blocks = system.blocks;
  view->mass_is_diagonal = system.mass_is_diagonal;
  view->stiffness_is_definite = system.stiffness_is_definite;
  view->sparsity = std::make_unique<dealii::SparsityPattern>();
  view->sparsity->copy_from(*system.sparsity);
  for (auto [to, from] :
       {std::pair{&view->mass, &system.mass}, std::pair{&view->damping, &system.damping},
        std::pair{&view->stiffness, &system.stiffness}})
  {
    to->reinit(*view->sparsity);
    to->copy_from(*from);
  }
  view->load.reinit(system.n_dofs());
  for (unsigned int i = 0; i < system.n_constraints(); ++i)
    if (i < active.size() && active[i])
      view->add_constraint(std::make_unique<HomogeneousConstraint>(*system.constraints[i],
                                                                   freeze, frozen_time));
  return view;
}

HalfExplicitStepMap::HalfExplicitStepMap(const SemiDiscreteSystem& system,
                                         const std::vector<bool>& active, const double dt,
                                         const ContactRows contact, const double t0)
    : dt(dt), view(homogeneous_view(system, active, contact == ContactRows::frozen, t0)),
      method(std::make_unique<HalfExplicitIntegrator>(*view, dt, 1))
{
}

HalfExplicitStepMap::~HalfExplicitStepMap() = default;

void HalfExplicitStepMap::apply(const double t_n, State& x)
{
  DynamicState s;
  s.t = t_n;
  s.q.swap(x.q);
  s.v.swap(x.v);
  s.a.reinit(view->n_dofs());
  s.lambda.assign(view->n_constraints(), 0.);
  s.active.assign(view->n_constraints(), true);
  method->initialize(s);
  method->set_previous_velocity(x.v_prev);
  method->advance();
  x.q = method->positions();
  x.v = method->velocities();
  x.v_prev = method->previous_velocities();
}

double growth_per_step(const SemiDiscreteSystem& system, const std::vector<bool>& active,
                       const double dt, const double t0, const unsigned int steps,
                       const ContactRows contact)
{
  HalfExplicitStepMap map(system, active, dt, contact, t0);
  const unsigned int n = system.n_dofs();
  HalfExplicitStepMap::State x;
  std::mt19937 random(17);
  std::uniform_real_distribution<double> uniform(-1., 1.);
  for (auto* y : {&x.q, &x.v, &x.v_prev})
  {
    y->reinit(n);
    for (auto& e : *y)
      e = uniform(random);
  }
  const double omega2 = 4. / (dt * dt);
  const auto norm = [&]()
  {
    // Four partial sums: one chain of additions would wait on each.
    double sum[4] = {0., 0., 0., 0.};
    for (unsigned int i = 0; i < n; ++i)
      sum[i % 4] +=
          omega2 * x.q[i] * x.q[i] + x.v[i] * x.v[i] + x.v_prev[i] * x.v_prev[i];
    return std::sqrt((sum[0] + sum[1]) + (sum[2] + sum[3]));
  };
  // log |x_k| accumulated with a normalisation every step; the growth is the
  // slope of its least-squares line over the second half (less sensitive to
  // the beating of the neutral modes than the ratio of two norms).
  double log_norm = 0.;
  const unsigned int first = steps / 2;
  double sk = 0., sy = 0., skk = 0., sky = 0.;
  for (unsigned int k = 0; k < steps; ++k)
  {
    map.apply(contact == ContactRows::moving ? t0 + k * dt : t0, x);
    const double size = norm();
    if (!(size > 0.) || !std::isfinite(size))
      return std::numeric_limits<double>::infinity();
    log_norm += std::log(size);
    const double scale = 1. / size;
    for (unsigned int i = 0; i < n; ++i)
    {
      x.q[i] *= scale;
      x.v[i] *= scale;
      x.v_prev[i] *= scale;
    }
    if (k >= first)
    {
      const double kk = k - first;
      sk += kk;
      sy += log_norm;
      skk += kk * kk;
      sky += kk * log_norm;
    }
  }
  const double count = steps - first;
  return std::exp((count * sky - sk * sy) / (count * skk - sk * sk));
}
} // namespace pantocat
