#pragma once

#include <deal.II/lac/vector.h>

#include <vector>

namespace pantocat
{
/**
 * The state of the semi-discrete system (35) at one time point: positions,
 * velocities, accelerations, the constraint forces lambda (0 for inactive
 * constraints) and the active set of the unilateral constraints.
 */
struct DynamicState
{
  double t = 0.;
  dealii::Vector<double> q, v, a;
  std::vector<double> lambda;
  std::vector<bool> active;
};
} // namespace pantocat
