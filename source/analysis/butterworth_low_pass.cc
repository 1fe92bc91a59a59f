#include <pantocat/analysis/butterworth_low_pass.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace pantocat
{
ButterworthLowPass::ButterworthLowPass(const double cutoff, const double sample_rate,
                                       const unsigned int order)
    : f_c(cutoff), f_s(sample_rate), n(order)
{
  if (!(cutoff > 0. && cutoff < 0.5 * sample_rate))
    throw std::invalid_argument("Butterworth cut-off must lie in (0, f_s/2)");
  if (order < 1 || order > 8)
    throw std::invalid_argument("Butterworth order must lie in 1..8");
  // Bilinear transform s -> (1/K)(z - 1)/(z + 1) of the prototype with cut-off
  // 1, pre-warped: K = tan(pi f_c / f_s). The poles lie on the unit circle at
  // exp(i pi (2k + n - 1)/(2n)), k = 1..n; the pair k, n + 1 - k gives
  // s^2 + 2 sin(pi (2k - 1)/(2n)) s + 1 (n = 3: s^2 + s + 1 and s + 1).
  const double K = std::tan(M_PI * f_c / f_s);
  for (unsigned int k = 1; k <= n / 2; ++k)
  {
    const double a = 2. * std::sin(M_PI * (2. * k - 1.) / (2. * n));
    const double norm = 1. / (1. + a * K + K * K);
    const double b0 = K * K * norm;
    sections.push_back(
        {b0, 2. * b0, b0, 2. * (K * K - 1.) * norm, (1. - a * K + K * K) * norm});
  }
  if (n % 2 == 1) // the real pole: 1/(s + 1)
  {
    const double b0 = K / (1. + K);
    sections.push_back({b0, b0, 0., (K - 1.) / (K + 1.), 0.});
  }
}

double ButterworthLowPass::gain(const double f) const
{
  const double r = std::tan(M_PI * f / f_s) / std::tan(M_PI * f_c / f_s);
  return 1. / std::sqrt(1. + std::pow(r, 2. * n));
}

void ButterworthLowPass::Section::apply(std::vector<double>& x) const
{
  if (x.empty())
    return;
  // Steady state for the constant input x_0 (the DC gain is 1).
  double z1 = (b1 - a1 + b2 - a2) * x[0], z2 = (b2 - a2) * x[0];
  for (double& value : x)
  {
    const double in = value;
    value = b0 * in + z1;
    z1 = b1 * in - a1 * value + z2;
    z2 = b2 * in - a2 * value;
  }
}

std::vector<double> ButterworthLowPass::filter(const std::vector<double>& x) const
{
  std::vector<double> y = x;
  for (const Section& s : sections)
    s.apply(y);
  return y;
}

std::vector<double>
ButterworthLowPass::filter_forward_backward(const std::vector<double>& x) const
{
  const std::size_t size = x.size();
  if (size < 2)
    return x;
  const auto samples = static_cast<std::size_t>(std::ceil(1.5 * n * f_s / f_c));
  const std::size_t pad = std::min(size - 1, samples);
  // Odd reflection about both ends: 2 x_0 - x_k, ..., x, ..., 2 x_{n-1} - x_{n-1-k}.
  std::vector<double> extended;
  extended.reserve(size + 2 * pad);
  for (std::size_t k = pad; k >= 1; --k)
    extended.push_back(2. * x[0] - x[k]);
  extended.insert(extended.end(), x.begin(), x.end());
  for (std::size_t k = 1; k <= pad; ++k)
    extended.push_back(2. * x[size - 1] - x[size - 1 - k]);

  std::vector<double> y = filter(extended);
  std::reverse(y.begin(), y.end());
  y = filter(y);
  std::reverse(y.begin(), y.end());
  return std::vector<double>(y.begin() + pad, y.begin() + pad + size);
}
} // namespace pantocat
