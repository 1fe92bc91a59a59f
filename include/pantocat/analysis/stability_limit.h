#pragma once

#include <pantocat/system/semi_discrete_system.h>

namespace pantocat
{
/**
 * The largest circular frequency omega_max of K x = omega^2 M x, computed
 * block by block (each body's M and K are banded) with the banded
 * generalized eigensolver. Constraints only lower the largest frequency
 * (interlacing), so 2/omega_max is a safe step-size limit for the
 * half-explicit method (Sec. 5.2).
 */
double largest_circular_frequency(const SemiDiscreteSystem& system);
} // namespace pantocat
