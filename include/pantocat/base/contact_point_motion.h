#pragma once

#include <cmath>

namespace pantocat
{
/**
 * The motion of the contact point along the track (Sec. 2.2): x_p(t) =
 * x_{p,0} + v_p t, or, with a speed ramp of T_r > 0 seconds, from rest at
 * the constant acceleration v_p / T_r until t = T_r, then at v_p:
 *
 *   x_p(t) = x_{p,0} + v_p t^2 / (2 T_r)      for t < T_r,
 *   x_p(t) = x_{p,0} + v_p (t - T_r / 2)      for t >= T_r.
 *
 * Position and velocity are continuous, so a pantograph that starts from the
 * static state at rest does not start with a jump in speed.
 */
struct ContactPointMotion
{
  double initial_position = 2.;
  double speed = 32.;
  double ramp_time = 0.; ///< T_r [s]; 0: at v_p from t = 0

  double position(const double t) const
  {
    return t < ramp_time ? initial_position + 0.5 * speed * t * t / ramp_time
                         : initial_position + speed * (t - 0.5 * ramp_time);
  }
  double velocity(const double t) const
  {
    return t < ramp_time ? speed * t / ramp_time : speed;
  }
  double acceleration(const double t) const
  {
    return t < ramp_time ? speed / ramp_time : 0.;
  }
  /**
   * The time t >= 0 at which x_p(t) = @p x (the inverse of position(), for
   * x >= x_{p,0}): inside the ramp t = sqrt(2 (x - x_{p,0}) T_r / v_p), after it
   * t = (x - x_{p,0}) / v_p + T_r / 2.
   */
  double time_at(const double x) const
  {
    const double distance = x - initial_position;
    if (distance < 0.5 * speed * ramp_time)
      return std::sqrt(2. * distance * ramp_time / speed);
    return distance / speed + 0.5 * ramp_time;
  }
};
} // namespace pantocat
