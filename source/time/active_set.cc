#include <pantocat/base/input_error.h>
#include <pantocat/time/active_set.h>

#include <algorithm>
#include <sstream>

namespace pantocat
{
ActiveSetIteration::ActiveSetIteration(const SemiDiscreteSystem& system,
                                       const unsigned int max_iterations)
    : system(system), max_iterations(max_iterations)
{
}

void ActiveSetIteration::start(const std::vector<bool>& active_at_start)
{
  at_start = active_at_start;
  current = active_at_start;
  // Bilateral constraints are always active.
  for (unsigned int i = 0; i < current.size(); ++i)
    if (!system.constraints[i]->is_unilateral())
      current[i] = true;
  visited.assign(1, current);
  update_indices();
}

void ActiveSetIteration::update_indices()
{
  indices.clear();
  for (unsigned int i = 0; i < current.size(); ++i)
    if (current[i])
      indices.push_back(i);
}

std::string ActiveSetIteration::describe(const std::vector<bool>& set) const
{
  std::ostringstream s;
  s << '{';
  bool first = true;
  for (unsigned int i = 0; i < set.size(); ++i)
    if (set[i])
    {
      s << (first ? "" : ", ") << system.constraints[i]->name();
      first = false;
    }
  s << '}';
  return s.str();
}

bool ActiveSetIteration::accept(const std::vector<double>& gaps_next,
                                const std::vector<double>& lambda, const double t,
                                const unsigned long step)
{
  std::vector<bool> next = current;
  bool changed = false;
  for (unsigned int i = 0; i < current.size(); ++i)
  {
    if (!system.constraints[i]->is_unilateral())
      continue;
    if (!current[i] && gaps_next[i] < 0.)
      next[i] = true, changed = true;
    else if (current[i] && at_start[i] && lambda[i] < 0.)
      next[i] = false, changed = true;
  }
  if (!changed)
    return true;
  std::ostringstream where;
  where << "at t = " << t << " s (step " << step << ")";
  if (std::find(visited.begin(), visited.end(), next) != visited.end())
    throw SimulationError("the active set of the unilateral constraints cycles " +
                          where.str() + " between " + describe(current) + " and " +
                          describe(next));
  if (visited.size() >= max_iterations)
    throw SimulationError("the active set did not settle in " +
                          std::to_string(max_iterations) + " iterations " + where.str() +
                          " (Time integration/Maximum active-set iterations)");
  visited.push_back(next);
  current = next;
  update_indices();
  return false;
}

unsigned int ActiveSetIteration::changes_in_step() const
{
  unsigned int n = 0;
  for (unsigned int i = 0; i < current.size(); ++i)
    n += current[i] != at_start[i];
  return n;
}
} // namespace pantocat
