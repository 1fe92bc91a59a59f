#pragma once

#include <vector>

namespace pantocat
{
/**
 * The second-order Butterworth low-pass filter, discretised by the bilinear
 * transform with the cut-off pre-warped (so the digital filter has exactly
 * |H| = 1/sqrt(2), -3.01 dB, at the cut-off), for a signal sampled at a
 * constant rate. The railway standards evaluate the contact force in a band
 * of 0 to 20 Hz (EN 50318, EN 50367): this is the filter for that purpose.
 *
 * filter_forward_backward() runs it forward and then backward over the whole
 * series (zero phase: peaks keep their time and place), so its gain is
 * |H|^2: 1/2 (-6.02 dB) at the cut-off, and the roll-off is 80 dB/decade.
 */
class ButterworthLowPass
{
public:
  /// @p cutoff and @p sample_rate in Hz; needs 0 < cutoff < sample_rate/2.
  ButterworthLowPass(double cutoff, double sample_rate);

  /**
   * The analytic gain |H(e^{i 2 pi f / f_s})| of one pass at frequency @p f:
   * 1/sqrt(1 + (tan(pi f/f_s) / tan(pi f_c/f_s))^4).
   */
  double gain(double f) const;

  /// One causal pass (direct form II transposed), started in the steady state of
  /// the first sample.
  std::vector<double> filter(const std::vector<double>& x) const;

  /**
   * Zero-phase filtering: forward, then backward. The ends are extended by odd
   * reflection over three cut-off periods (at most the signal length less one)
   * and each pass starts in the steady state of its first sample: a constant
   * passes unchanged, and the start-up transient (decay rate 2 pi f_c/sqrt(2))
   * has fallen to e^-13 when the pass reaches the data.
   */
  std::vector<double> filter_forward_backward(const std::vector<double>& x) const;

  double cutoff() const { return f_c; }

private:
  double f_c, f_s;
  double b0, b1, b2, a1,
      a2; ///< y_n = b0 x_n + b1 x_{n-1} + b2 x_{n-2} - a1 y_{n-1} - a2 y_{n-2}
};
} // namespace pantocat
