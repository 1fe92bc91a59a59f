#pragma once

#include <pantocat/system/semi_discrete_system.h>

#include <vector>

namespace pantocat
{
/**
 * The states (G, G_t, G_tt, z, ...) of all constraints at one time point,
 * reused from step to step: constraints with constant rows (droppers) are
 * evaluated once, time-dependent ones (the contact) at every call.
 */
class ConstraintEvaluator
{
public:
  explicit ConstraintEvaluator(const SemiDiscreteSystem& system);

  /// Evaluates the time-dependent constraints at @p t up to time derivative @p max_order.
  const std::vector<ConstraintState>& at(double t, unsigned int max_order = 2);

  const std::vector<ConstraintState>& states() const { return cache; }
  /// True if states() are those at @p t (the last call of at() was for @p t).
  bool holds(const double t) const { return evaluated && last_t == t; }

private:
  const SemiDiscreteSystem& system;
  std::vector<ConstraintState> cache;
  std::vector<unsigned int> time_dependent; ///< the constraints evaluated at each call
  bool evaluated = false;
  double last_t = 0.;
  unsigned int last_order = 0;
};
} // namespace pantocat
