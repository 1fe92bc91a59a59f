#include <pantocat/analysis/butterworth_low_pass.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace pantocat
{
ButterworthLowPass::ButterworthLowPass(const double cutoff, const double sample_rate)
    : f_c(cutoff), f_s(sample_rate)
{
  if (!(cutoff > 0. && cutoff < 0.5 * sample_rate))
    throw std::invalid_argument("Butterworth cut-off must lie in (0, f_s/2)");
  // Bilinear transform of H(s) = 1/(s^2 + sqrt(2) s + 1), s scaled by the
  // pre-warped cut-off K = tan(pi f_c / f_s).
  const double K = std::tan(M_PI * f_c / f_s);
  const double norm = 1. / (1. + std::sqrt(2.) * K + K * K);
  b0 = K * K * norm;
  b1 = 2. * b0;
  b2 = b0;
  a1 = 2. * (K * K - 1.) * norm;
  a2 = (1. - std::sqrt(2.) * K + K * K) * norm;
}

double ButterworthLowPass::gain(const double f) const
{
  const double r = std::tan(M_PI * f / f_s) / std::tan(M_PI * f_c / f_s);
  return 1. / std::sqrt(1. + r * r * r * r);
}

std::vector<double> ButterworthLowPass::filter(const std::vector<double>& x) const
{
  std::vector<double> y(x.size());
  if (x.empty())
    return y;
  // Steady state for the constant input x_0 (the DC gain is 1).
  double z1 = (b1 - a1 + b2 - a2) * x[0], z2 = (b2 - a2) * x[0];
  for (std::size_t n = 0; n < x.size(); ++n)
  {
    y[n] = b0 * x[n] + z1;
    z1 = b1 * x[n] - a1 * y[n] + z2;
    z2 = b2 * x[n] - a2 * y[n];
  }
  return y;
}

std::vector<double>
ButterworthLowPass::filter_forward_backward(const std::vector<double>& x) const
{
  const std::size_t n = x.size();
  if (n < 2)
    return x;
  const auto periods = static_cast<std::size_t>(std::ceil(3. * f_s / f_c));
  const std::size_t pad = std::min(n - 1, periods);
  // Odd reflection about both ends: 2 x_0 - x_k, ..., x, ..., 2 x_{n-1} - x_{n-1-k}.
  std::vector<double> extended;
  extended.reserve(n + 2 * pad);
  for (std::size_t k = pad; k >= 1; --k)
    extended.push_back(2. * x[0] - x[k]);
  extended.insert(extended.end(), x.begin(), x.end());
  for (std::size_t k = 1; k <= pad; ++k)
    extended.push_back(2. * x[n - 1] - x[n - 1 - k]);

  std::vector<double> y = filter(extended);
  std::reverse(y.begin(), y.end());
  y = filter(y);
  std::reverse(y.begin(), y.end());
  return std::vector<double>(y.begin() + pad, y.begin() + pad + n);
}
} // namespace pantocat
