#include <pantocat/base/input_error.h>
#include <pantocat/time/active_set.h>

#include <algorithm>
#include <cstring>
#include <sstream>

namespace pantocat
{
ActiveSetIteration::ActiveSetIteration(const SemiDiscreteSystem& system,
                                       const unsigned int max_iterations,
                                       const ClosingConstraint closing,
                                       const bool allow_touching)
    : system(system), max_iterations(max_iterations), closing(closing),
      allow_touching(allow_touching)
{
  for (const auto& c : system.constraints)
  {
    unilateral.push_back(c->is_unilateral());
    compliant.push_back(c->is_compliant());
    // Bilateral constraints are always active (engaged if compliant).
    held_status.push_back(c->is_compliant() ? Status::engaged : Status::active);
    if (c->is_unilateral())
      unilateral_indices.push_back(unilateral.size() - 1);
  }
}

void ActiveSetIteration::start(const std::vector<bool>& active_at_start)
{
  const std::size_t m = active_at_start.size();
  at_start.resize(m);
  current.resize(m);
  unsigned int changes = 0;
  for (std::size_t i = 0; i < m; ++i)
  {
    const char held = active_at_start[i];
    at_start[i] = held;
    const bool holds_now = held || !unilateral[i];
    current[i] = holds_now ? held_status[i] : Status::inactive;
    changes += holds_now != static_cast<bool>(held);
  }
  changes_at_start = changes;
  released.assign(m, false);
  visited.resize(1); // keeps the capacity: no allocation per step
  visited[0] = current;
  // Most steps start from the set the step before started from.
  static_assert(sizeof(Status) == sizeof(char));
  if (indexed.size() != m ||
      (m > 0 && std::memcmp(current.data(), indexed.data(), m) != 0))
    update_indices();
}

const std::vector<bool>& ActiveSetIteration::active() const
{
  if (!holds_flags_current)
  {
    holds_flags.assign(holds.begin(), holds.end());
    holds_flags_current = true;
  }
  return holds_flags;
}

void ActiveSetIteration::update_indices()
{
  indices.clear();
  force.clear();
  engaged.clear();
  holds.resize(current.size());
  indexed.resize(current.size());
  holds_flags_current = false;
  for (unsigned int i = 0; i < current.size(); ++i)
  {
    indexed[i] = static_cast<char>(current[i]);
    holds[i] = current[i] != Status::inactive;
    if (current[i] == Status::engaged)
      engaged.push_back(i);
    else if (holds[i] && current[i] != Status::impacting)
      indices.push_back(i);
    if (current[i] == Status::active)
      force.push_back(i);
  }
}

std::string ActiveSetIteration::describe(const std::vector<Status>& set) const
{
  std::ostringstream s;
  s << '{';
  bool first = true;
  for (unsigned int i = 0; i < set.size(); ++i)
    if (set[i] != Status::inactive)
    {
      s << (first ? "" : ", ") << system.constraints[i]->name()
        << (set[i] == Status::touching    ? " (touching)"
            : set[i] == Status::engaged   ? " (engaged spring)"
            : set[i] == Status::impacting ? " (impact)"
                                          : "");
      first = false;
    }
  s << '}';
  return s.str();
}

ActiveSetIteration::Status ActiveSetIteration::compliant_status(const unsigned int i,
                                                                const double gap,
                                                                const double rate) const
{
  const Constraint& c = *system.constraints[i];
  // Engaged iff the law max(0, -k g - c dg/dt) (g < 0) is positive.
  return gap < 0. && c.trial_force(gap, rate) > 0. ? Status::engaged : Status::inactive;
}

bool ActiveSetIteration::accept(const std::vector<double>& gaps_next,
                                const std::vector<double>& lambda, const double t,
                                const unsigned long step,
                                const std::vector<double>& gap_rates)
{
  next = current;
  bool changed = false;
  for (const unsigned int i : unilateral_indices) // bilateral ones always hold
  {
    if (compliant[i])
    {
      if (gap_rates.empty())
        continue; // an explicit force: the integrator's own business
      next[i] = compliant_status(i, gaps_next[i], gap_rates[i]);
      changed = changed || next[i] != current[i];
      continue;
    }
    if (current[i] == Status::inactive && gaps_next[i] < 0.)
    {
      // Released in this step for a negative force, yet penetrating without
      // it: touching. Otherwise it closes (an impact).
      if (!allow_touching)
        next[i] = Status::active; // the paper's iteration
      else if (released[i] || closing == ClosingConstraint::touching)
        next[i] = Status::touching;
      else
        next[i] = Status::impacting;
      changed = true;
    }
    else if (current[i] == Status::active && at_start[i] && lambda[i] < 0.)
    {
      next[i] = Status::inactive;
      released[i] = true;
      changed = true;
    }
  }
  if (!changed)
    return true;
  std::ostringstream where;
  where << "at t = " << t << " s (step " << step << ")";
  std::string switching;
  for (unsigned int i = 0; i < next.size(); ++i)
    if (next[i] != current[i])
      switching += (switching.empty() ? "" : ", ") + system.constraints[i]->name();
  where << " switching " << switching;
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
  // Without a trial rejected, the set is the one start() made from J_n.
  if (visited.size() == 1)
    return changes_at_start;
  unsigned int n = 0;
  for (unsigned int i = 0; i < holds.size(); ++i)
    n += holds[i] != at_start[i];
  return n;
}

bool ActiveSetIteration::impact_in_step() const
{
  // start() holds a constraint not in J_n only if it is bilateral: an impact
  // needs a trial rejected.
  if (visited.size() == 1)
    return false;
  for (unsigned int i = 0; i < holds.size(); ++i)
    if (holds[i] && !at_start[i] && unilateral[i] && !compliant[i])
      return true;
  return false;
}

std::vector<unsigned int> ActiveSetIteration::holding_indices() const
{
  std::vector<unsigned int> h;
  for (unsigned int i = 0; i < current.size(); ++i)
    if (holds[i] && current[i] != Status::engaged)
      h.push_back(i);
  return h;
}

void clamp_compliant_forces(const SemiDiscreteSystem& system, std::vector<double>& lambda)
{
  for (unsigned int i = 0; i < lambda.size(); ++i)
    if (lambda[i] < 0. && system.constraints[i]->is_compliant() &&
        system.constraints[i]->is_unilateral())
      lambda[i] = 0.;
}

double damping_ratio(const Constraint& c)
{
  return c.is_compliant() ? c.compliance().damping / c.compliance().stiffness : 0.;
}
} // namespace pantocat
