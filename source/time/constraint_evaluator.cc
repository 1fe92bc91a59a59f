#include <pantocat/time/constraint_evaluator.h>

namespace pantocat
{
ConstraintEvaluator::ConstraintEvaluator(const SemiDiscreteSystem& system)
    : system(system), cache(system.n_constraints())
{
  for (unsigned int i = 0; i < cache.size(); ++i)
  {
    system.constraints[i]->evaluate(0., cache[i]);
    if (system.constraints[i]->depends_on_time())
      time_dependent.push_back(i);
  }
}

const std::vector<ConstraintState>& ConstraintEvaluator::at(const double t,
                                                            const unsigned int max_order)
{
  // Asked again for the same time point: the rows are already there.
  if (evaluated && t == last_t && max_order <= last_order)
    return cache;
  for (const unsigned int i : time_dependent)
    system.constraints[i]->evaluate(t, cache[i], max_order);
  evaluated = true;
  last_t = t;
  last_order = max_order;
  return cache;
}
} // namespace pantocat
