#pragma once

#include <deal.II/lac/vector.h>

#include <vector>

namespace pantocat
{
/**
 * The state of the semi-discrete system (35) at one time point: positions,
 * velocities, accelerations, the constraint forces lambda (0 for inactive
 * constraints) and the active set of the unilateral constraints.
 *
 * Impacts (Sec. 5.3: a closing unilateral constraint is an inelastic impact).
 * The velocities jump there by M^-1 G^T P: P is the impulse [N s] that each
 * constraint delivers at the impact, kept apart from the force lambda (a
 * finite force; the impulse is a Dirac measure in the force's time history).
 * `impulse` holds P per constraint at a time point where some constraint
 * closed since the previous one (the closing ones and the others that hold
 * share it, like the contact when a dropper re-tensions); it is empty at the
 * other time points.
 */
struct DynamicState
{
  double t = 0.;
  dealii::Vector<double> q, v, a;
  std::vector<double> lambda;
  std::vector<bool> active;
  std::vector<double> impulse;
};
} // namespace pantocat
