#include <pantocat/analysis/moving_load_series.h>
#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>

#include <deal.II/base/quadrature_lib.h>

#include <cmath>

namespace pantocat
{
namespace
{
/// c = int delta_eps(s) cos(k s) ds = 2 int_0^eps delta_eps(s) cos(k s) ds (Gauss rule
/// on pieces short against the wave length 2 pi / k).
double load_factor(const SmoothedDelta& delta, const double k)
{
  const double eps = delta.epsilon();
  const unsigned int pieces = 8 + static_cast<unsigned int>(k * eps);
  const dealii::QGauss<1> gauss(12);
  double c = 0.;
  for (unsigned int p = 0; p < pieces; ++p)
    for (unsigned int q = 0; q < gauss.size(); ++q)
    {
      const double s = eps * (p + gauss.point(q)[0]) / pieces;
      c += 2. * eps / pieces * gauss.weight(q) * delta.value(s) * std::cos(k * s);
    }
  return c;
}
} // namespace

MovingLoadSeries::MovingLoadSeries(const WireParameters& wire, const double span,
                                   const double force, const ContactPointMotion& motion,
                                   const std::optional<SmoothedDelta>& delta,
                                   const unsigned int n_modes)
    : span(span), motion(motion)
{
  require(motion.ramp_time == 0., "Pantograph/Speed ramp", motion.ramp_time,
          "the series of the moving load is for a constant speed; allowed: 0");
  require(motion.speed < wire.wave_speed(), "Pantograph/Speed", motion.speed,
          "the series of the moving load needs a speed below the wave speed " +
              number_to_string(wire.wave_speed()) + " m/s");
  const double rho_a = wire.mass_per_length;
  for (unsigned int n = 1; n <= n_modes; ++n)
  {
    const double kn = n * M_PI / span;
    const double w2 =
        (wire.tension * kn * kn + wire.bending_stiffness * std::pow(kn, 4)) / rho_a;
    const double Omega = kn * motion.speed;
    const double c = delta ? load_factor(*delta, kn) : 1.;
    k.push_back(kn);
    omega.push_back(std::sqrt(w2));
    amplitude.push_back(2. * force * c / (rho_a * span) / (w2 - Omega * Omega));
  }
  // delta_eps makes c_n decay like (k_n eps)^-3 beyond k_n eps ~ 1, the modal
  // amplitudes like n^-5: drop the modes below 1e-9 of the first (their tail
  // adds below 1e-7 of w); a point load keeps all n_modes (tail O(1/n_modes)).
  std::size_t last = 0;
  for (std::size_t n = 0; n < amplitude.size(); ++n)
    if (std::abs(amplitude[n]) > 1e-9 * std::abs(amplitude[0]))
      last = n;
  k.resize(last + 1);
  omega.resize(last + 1);
  amplitude.resize(last + 1);
}

double MovingLoadSeries::displacement(const double x, const double t) const
{
  double w = 0.;
  for (std::size_t n = 0; n < k.size(); ++n)
  {
    const double Omega = k[n] * motion.speed, theta = k[n] * motion.initial_position;
    const double q =
        amplitude[n] *
        (std::sin(Omega * t + theta) - std::sin(theta) * std::cos(omega[n] * t) -
         Omega / omega[n] * std::cos(theta) * std::sin(omega[n] * t));
    w += q * std::sin(k[n] * x);
  }
  return w;
}
} // namespace pantocat
