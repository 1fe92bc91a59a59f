#pragma once

namespace pantocat
{
/**
 * The unconstrained step of (40) at unknown @p i: v*_i = v_prev,i + 2 dt a_i,
 * q*_i = q_i + dt (v_i + v*_i)/2, with @p two_dt = 2 dt and @p half_dt =
 * dt/2. Every place that predicts a row (the force sweeps, the rows predicted
 * again, the step without a fused sweep, DisjointFixedConstraints) calls
 * this (for all unknowns at once in a vectorised loop: FastHalfExplicitStepSystem's
 * predict_all()): the same operations in the same order, so q*, v* are the
 * same to the bit wherever they are made.
 */
[[gnu::always_inline]] inline void
predict_unconstrained(const int i, const double a, const double two_dt,
                      const double half_dt, const double* __restrict q,
                      const double* __restrict v, const double* __restrict vp,
                      double* __restrict q_new, double* __restrict v_new)
{
  const double vn = vp[i] + two_dt * a;
  v_new[i] = vn;
  q_new[i] = q[i] + half_dt * (v[i] + vn);
}
} // namespace pantocat
