#pragma once

namespace pantocat
{
/// The motion of the contact point along the track, x_p(t) = x_{p,0} + v_p t (Sec. 2.2).
struct ContactPointMotion
{
  double initial_position = 2.;
  double speed = 32.;

  double position(double t) const { return initial_position + speed * t; }
  double velocity(double) const { return speed; }
  double acceleration(double) const { return 0.; }
};
} // namespace pantocat
