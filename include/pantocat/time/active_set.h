#pragma once

#include <pantocat/system/semi_discrete_system.h>

#include <string>
#include <vector>

namespace pantocat
{
/**
 * The active-set strategy of Sec. 5.3 for one time step t_n -> t_{n+1}.
 *
 * Start with J_{n+1} := J_n. After a trial step:
 *  - an inactive unilateral constraint with g_i(t_{n+1}, q_{n+1}) < 0 becomes
 *    active (contact or a taut dropper again: an inelastic impact, since the
 *    velocity constraint g^(I) = 0 then holds at t_{n+1});
 *  - a constraint of J_n with lambda_i < 0 becomes inactive.
 * A constraint added in this step is not released in the same step: its
 * multiplier on acceleration level may be negative at the impact, and
 * releasing it would undo the impact and cycle.
 * All violations are toggled together and the step is repeated; a set seen
 * before in the same step, or more than the allowed number of repetitions,
 * stops the run with a SimulationError that names time, step and constraints.
 */
class ActiveSetIteration
{
public:
  ActiveSetIteration(const SemiDiscreteSystem& system, unsigned int max_iterations);

  /// Begin a step from the active set J_n.
  void start(const std::vector<bool>& active_at_start);

  /**
   * Checks a trial step; returns true if it is accepted, otherwise updates
   * the active set for the repetition.
   */
  bool accept(const std::vector<double>& gaps_next, const std::vector<double>& lambda,
              double t, unsigned long step);

  const std::vector<bool>& active() const { return current; }
  /// Indices of the active constraints.
  const std::vector<unsigned int>& active_indices() const { return indices; }
  /// Number of constraints whose state changed in the accepted step.
  unsigned int changes_in_step() const;
  unsigned int iterations_in_step() const { return visited.size(); }

private:
  void update_indices();
  std::string describe(const std::vector<bool>& set) const;

  const SemiDiscreteSystem& system;
  unsigned int max_iterations;
  std::vector<bool> at_start, current;
  std::vector<unsigned int> indices;
  std::vector<std::vector<bool>> visited;
};
} // namespace pantocat
