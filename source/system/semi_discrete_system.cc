#include <pantocat/base/input_error.h>
#include <pantocat/system/semi_discrete_system.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>

namespace pantocat
{
void SemiDiscreteSystem::set_blocks(const std::vector<const BlockOperator*>& bodies)
{
  blocks.clear();
  unsigned int n = 0;
  mass_is_diagonal = true;
  stiffness_is_definite = true;
  for (const BlockOperator* b : bodies)
  {
    blocks.push_back({b->name, n, b->size()});
    n += b->size();
    mass_is_diagonal = mass_is_diagonal && b->mass_is_diagonal;
    stiffness_is_definite = stiffness_is_definite && b->stiffness_is_definite;
  }
  dealii::DynamicSparsityPattern dsp(n, n);
  // Row by row: a deal.II iterator's row() is a binary search.
  for (unsigned int k = 0; k < bodies.size(); ++k)
    for (unsigned int i = 0; i < blocks[k].size; ++i)
      for (auto it = bodies[k]->sparsity->begin(i); it != bodies[k]->sparsity->end(i);
           ++it)
        dsp.add(blocks[k].first + i, blocks[k].first + it->column());
  sparsity = std::make_unique<dealii::SparsityPattern>();
  sparsity->copy_from(dsp);
  mass.reinit(*sparsity);
  damping.reinit(*sparsity);
  stiffness.reinit(*sparsity);
  load.reinit(n);
  for (unsigned int k = 0; k < bodies.size(); ++k)
  {
    const unsigned int o = blocks[k].first;
    const BlockOperator& b = *bodies[k];
    for (const dealii::SparseMatrix<double>* m : {&b.mass, &b.damping, &b.stiffness})
    {
      dealii::SparseMatrix<double>& target =
          m == &b.mass ? mass : (m == &b.damping ? damping : stiffness);
      for (unsigned int i = 0; i < b.size(); ++i)
        for (auto it = m->begin(i); it != m->end(i); ++it)
          target.set(o + i, o + it->column(), it->value());
    }
    for (unsigned int i = 0; i < b.size(); ++i)
      load(o + i) = b.load(i);
  }
}

void SemiDiscreteSystem::add_constraint(std::unique_ptr<Constraint> constraint)
{
  constraints.push_back(std::move(constraint));
}

void SemiDiscreteSystem::add_time_dependent_load(std::unique_ptr<TimeDependentLoad> f)
{
  time_dependent_loads.push_back(std::move(f));
}

void SemiDiscreteSystem::load_at(const double t, dealii::Vector<double>& f) const
{
  f = load;
  for (const auto& extra : time_dependent_loads)
    extra->add_to(t, f);
}

bool SemiDiscreteSystem::has_block(const std::string& name) const
{
  for (const auto& b : blocks)
    if (b.name == name)
      return true;
  return false;
}

const DofBlock& SemiDiscreteSystem::block(const std::string& name) const
{
  for (const auto& b : blocks)
    if (b.name == name)
      return b;
  throw std::logic_error("no block named '" + name + "' in the semi-discrete system");
}

double SemiDiscreteSystem::potential_of_loads_and_springs(const dealii::Vector<double>& q,
                                                          const double t) const
{
  double work = load * q;
  if (has_time_dependent_load())
  {
    dealii::Vector<double> f;
    load_at(t, f);
    work = f * q;
  }
  double springs = 0.;
  ConstraintState state;
  for (const auto& c : constraints)
    if (c->is_compliant())
    {
      c->evaluate(t, state, 0);
      springs += c->strain_energy(state.position_residual(q));
    }
  return springs - work;
}

double SemiDiscreteSystem::energy(const dealii::Vector<double>& q,
                                  const dealii::Vector<double>& v, const double t) const
{
  return 0.5 * mass.matrix_norm_square(v) + 0.5 * stiffness.matrix_norm_square(q) +
         potential_of_loads_and_springs(q, t);
}

bool SemiDiscreteSystem::has_compliant_constraints() const
{
  for (const auto& c : constraints)
    if (c->is_compliant())
      return true;
  return false;
}
} // namespace pantocat
