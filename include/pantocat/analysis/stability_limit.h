#pragma once

#include <pantocat/system/semi_discrete_system.h>

#include <string>

namespace pantocat
{
/**
 * The largest circular frequency omega_max of K x = omega^2 M x, computed
 * block by block (each body's M and K are banded) with the banded
 * generalized eigensolver. Constraints only lower the largest frequency
 * (interlacing), so 2/omega_max is a safe step-size limit for the
 * half-explicit method (Sec. 5.2).
 *
 * Compliant constraints (Constraint::is_compliant) are explicit forces of
 * that method and, engaged, add k_i G_i^T G_i to K: omega_max^2 is then
 * bounded by Weyl's inequality, all of them taken as engaged, by
 * omega_max^2(K, M) + compliant_frequency_bound(system).
 */
double largest_circular_frequency(const SemiDiscreteSystem& system);

/**
 * sum_i k_i G_i M^-1 G_i^T over the compliant constraints at time @p t: an
 * upper bound of what their springs add to omega_max^2 (each term the one
 * non-zero eigenvalue of M^-1 k_i G_i^T G_i). A moving constraint's row
 * (penalty contact) is taken at @p t; for the lumped FDM mass its value
 * between two nodes, sum_j w_j^2 / m_j with sum_j w_j = 1, w_j >= 0, does
 * not exceed that at the lightest node. Damping c_i is not included. 0
 * without compliant constraints.
 */
double compliant_frequency_bound(const SemiDiscreteSystem& system, double t = 0.);

/**
 * For the step-size refusal: ", including the compliant constraints
 * (stiffest: '<name>', k = <k> N/m), explicit forces of this method that
 * raise omega_max by k G M^-1 G^T" if @p system has compliant constraints,
 * else "".
 */
std::string compliant_stiffness_note(const SemiDiscreteSystem& system);
} // namespace pantocat
