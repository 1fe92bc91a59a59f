#pragma once

#include <vector>

namespace pantocat
{
/**
 * The Butterworth low-pass filter of order n (1 to 8), discretised by the
 * bilinear transform with the cut-off pre-warped, for a signal sampled at a
 * constant rate: a cascade of second-order sections (and one first-order
 * section for odd n), one per pair of the analog prototype's poles. The
 * digital filter has exactly |H| = 1/sqrt(1 + r^(2n)), r = tan(pi f/f_s) /
 * tan(pi f_c/f_s): 1/sqrt(2) (-3.01 dB) at the cut-off for every n.
 *
 * The railway standards evaluate the contact force in a band of 0 to 20 Hz
 * (EN 50318, EN 50367); the reference section S55 asks for the fourth order
 * run forwards and backwards (doc/evaluation.md).
 *
 * filter_forward_backward() runs it forward and then backward over the whole
 * series (zero phase: peaks keep their time and place), so its gain is
 * |H|^2 = 1/(1 + r^(2n)): 1/2 (-6.02 dB) at the cut-off, and the roll-off is
 * 40 n dB/decade.
 */
class ButterworthLowPass
{
public:
  /// @p cutoff and @p sample_rate in Hz; needs 0 < cutoff < sample_rate/2 and
  /// 1 <= @p order <= 8 (std::invalid_argument otherwise).
  ButterworthLowPass(double cutoff, double sample_rate, unsigned int order);

  /**
   * The analytic gain |H(e^{i 2 pi f / f_s})| of one pass at frequency @p f:
   * 1/sqrt(1 + (tan(pi f/f_s) / tan(pi f_c/f_s))^(2n)).
   */
  double gain(double f) const;

  /// One causal pass (each section in direct form II transposed), started in
  /// the steady state of the first sample.
  std::vector<double> filter(const std::vector<double>& x) const;

  /**
   * Zero-phase filtering: forward, then backward. The ends are extended by odd
   * reflection over 1.5 n cut-off periods (at most the signal length less one)
   * and each pass starts in the steady state of its first sample: a constant
   * passes unchanged, and the start-up transient of the slowest pole (decay
   * rate 2 pi f_c sin(pi/(2n))) has fallen below e^-13 (n >= 2) when the pass
   * reaches the data.
   */
  std::vector<double> filter_forward_backward(const std::vector<double>& x) const;

  double cutoff() const { return f_c; }
  unsigned int order() const { return n; }

private:
  /**
   * One section: y_k = b0 x_k + b1 x_{k-1} + b2 x_{k-2} - a1 y_{k-1} - a2 y_{k-2}
   * (b2 = a2 = 0 for the first-order section); DC gain 1.
   */
  struct Section
  {
    double b0, b1, b2, a1, a2;
    /// One causal pass, started in the steady state of x_0.
    void apply(std::vector<double>& x) const;
  };

  double f_c, f_s;
  unsigned int n;
  std::vector<Section> sections;
};
} // namespace pantocat
