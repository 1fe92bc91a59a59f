// Output of a run (issue 8): the zero-phase Butterworth low pass against its
// analytic response, the contact-force statistics against hand-computed values,
// the ParaView time series (files, physical times, first frame = static
// profile), the progress line, and the log-log plot helper.
#include "support/catenary_system_builder.h"
#include <pantocat/analysis/butterworth_low_pass.h>
#include <pantocat/analysis/static_equilibrium.h>
#include <pantocat/app/program_parameters.h>
#include <pantocat/base/input_error.h>
#include <pantocat/io/csv_number.h>
#include <pantocat/io/plot_data.h>
#include <pantocat/io/plots.h>
#include <pantocat/io/progress_meter.h>
#include <pantocat/io/vtu_time_series_writer.h>
#include <pantocat/io/wire_output.h>
#include <pantocat/simulation/case_runner.h>
#include <pantocat/simulation/contact_statistics.h>

#include <deal.II/base/utilities.h>

#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <random>
#include <regex>
#include <sstream>

using namespace pantocat;

namespace
{
constexpr double fs = 2000.; // sample rate [Hz] of the filter tests
constexpr double fc = 20.;   // cut-off [Hz]

std::vector<double> sine(const double f, const std::size_t n, const double amplitude = 1.)
{
  std::vector<double> x(n);
  for (std::size_t k = 0; k < n; ++k)
    x[k] = amplitude * std::sin(2. * M_PI * f * k / fs);
  return x;
}

/**
 * Amplitude and phase of the component at @p f in y[first, first + count):
 * a discrete Fourier coefficient, exact for a sinusoid when the window holds
 * an integer number of its periods.
 */
std::pair<double, double> component(const std::vector<double>& y, const double f,
                                    const std::size_t first, const std::size_t count)
{
  double s = 0., c = 0.;
  for (std::size_t k = first; k < first + count; ++k)
  {
    s += y[k] * std::sin(2. * M_PI * f * k / fs);
    c += y[k] * std::cos(2. * M_PI * f * k / fs);
  }
  return {2. * std::hypot(s, c) / count, std::atan2(c, s)};
}
} // namespace

// A 4 s signal sampled at 2 kHz; amplitudes measured over the middle 2 s,
// where the start-up transient of each pass (slowest decay rate 2 pi f_c
// sin(pi/(2n)): 89/s for n = 2, 48/s for n = 4, so below e^-24 after 0.5 s
// from either end of the padded signal) has gone: the measured gain must
// equal the analytic |H(f)|^2 = 1/(1 + r^(2n)) of the bilinear-transform
// Butterworth to 1e-6 (relative; round-off and the transient are far below),
// for the second order and the fourth (S55's).
TEST(ButterworthLowPass, ForwardBackwardGainIsTheSquaredAnalyticResponse)
{
  for (const unsigned int order : {2u, 4u})
  {
    const ButterworthLowPass filter(fc, fs, order);
    // Pre-warped design: exactly -3.01 dB per pass at the cut-off, -6.02 dB for two.
    EXPECT_NEAR(filter.gain(fc), 1. / std::sqrt(2.), 1e-15);
    for (const double f : {2., 10., 20., 40., 60., 100.})
    {
      const auto y = filter.filter_forward_backward(sine(f, 8000));
      const auto [amplitude, phase] = component(y, f, 2000, 4000);
      const double expected = std::pow(filter.gain(f), 2);
      EXPECT_NEAR(amplitude / expected, 1., 1e-6) << "n = " << order << ", f = " << f;
      // Zero phase: the forward and backward phase shifts cancel.
      EXPECT_NEAR(phase, 0., 1e-6) << "n = " << order << ", f = " << f << " Hz";
    }
    // The figures the field quotes: 0.5 (-6.02 dB) at f_c, passband at 2 Hz
    // within 1e-4 of 1.
    EXPECT_NEAR(
        component(filter.filter_forward_backward(sine(fc, 8000)), fc, 2000, 4000).first,
        0.5, 1e-6);
    EXPECT_GT(std::pow(filter.gain(2.), 2), 1. - 1e-4);
  }
  // Stopband at 100 Hz (5 f_c): r = 5.04 (pre-warped), |H|^2 = 1/(1 + r^(2n)):
  // 1.6e-3 (-56 dB) for n = 2, 2.4e-6 (-112 dB) for n = 4.
  EXPECT_NEAR(std::pow(ButterworthLowPass(fc, fs, 2).gain(100.), 2), 1.55e-3, 0.05e-3);
  EXPECT_NEAR(std::pow(ButterworthLowPass(fc, fs, 4).gain(100.), 2), 2.4e-6, 0.1e-6);
}

TEST(ButterworthLowPass, OnePassHasTheAnalyticGainAndAConstantPassesUnchanged)
{
  // Every order 1..8 (odd ones with a first-order section): the causal pass
  // has the steady-state amplitude |H(f)| (1e-6, as above), a constant comes
  // through to round-off (DC gain 1, a steady-state start).
  for (unsigned int order = 1; order <= 8; ++order)
  {
    const ButterworthLowPass filter(fc, fs, order);
    for (const double f : {10., 20., 60.})
      EXPECT_NEAR(component(filter.filter(sine(f, 8000)), f, 4000, 4000).first /
                      filter.gain(f),
                  1., 1e-6)
          << "n = " << order << ", f = " << f << " Hz";
    for (const double y : filter.filter_forward_backward(std::vector<double>(500, 72.5)))
      EXPECT_NEAR(y, 72.5, 1e-10) << "n = " << order;
  }
  EXPECT_THROW(ButterworthLowPass(1000., fs, 2), std::invalid_argument); // at Nyquist
  EXPECT_THROW(ButterworthLowPass(fc, fs, 0), std::invalid_argument);
  EXPECT_THROW(ButterworthLowPass(fc, fs, 9), std::invalid_argument);
}

namespace
{
/**
 * 1000 points, dt = 1 ms, x_p = 2 + 10 t: lambda alternates 80 N / 120 N
 * (mean 100, std 20) except points 100..149, where the contact is lost
 * (lambda = 0). By hand: mean = 475 * 200 / 1000 = 95 N; E[lambda^2] =
 * 475 * (6400 + 14400) / 1000 = 9880 N^2, so std = sqrt(9880 - 95^2) =
 * sqrt(855) N; without contact 50 of 1000 points = 5 %.
 */
ContactForceSeries synthetic_series()
{
  ContactForceSeries s;
  for (unsigned int n = 0; n < 1000; ++n)
  {
    s.t.push_back(1e-3 * n);
    s.x_p.push_back(2. + 10. * s.t.back());
    const bool lost = n >= 100 && n < 150;
    s.lambda_p.push_back(lost ? 0. : (n % 2 == 0 ? 80. : 120.));
    s.in_contact.push_back(!lost);
  }
  return s;
}
} // namespace

// Exact figures: only round-off of 1000 sums (1e-12 relative).
TEST(ContactForceStatistics, WholeRunMatchesHandComputedValues)
{
  const auto s = evaluate_contact_force(synthetic_series(), StatisticsParameters{},
                                        EvaluationWindow{});
  const ForceFigures& r = s.raw;
  const double sigma = std::sqrt(855.);
  EXPECT_NEAR(r.mean, 95., 1e-12 * 95.);
  EXPECT_NEAR(r.std, sigma, 1e-12 * sigma);
  EXPECT_NEAR(r.mean_minus_3std, 95. - 3. * sigma, 1e-10);
  EXPECT_NEAR(r.mean_plus_3std, 95. + 3. * sigma, 1e-10);
  EXPECT_EQ(r.max, 120.);
  EXPECT_EQ(r.min, 0.);
  EXPECT_NEAR(r.contact_loss_percent, 5., 1e-12);
  EXPECT_EQ(r.n_points, 1000u);
  EXPECT_EQ(s.filter_cutoff_hz, 0.);
  EXPECT_FALSE(s.filtered.has_value()); // no cut-off: no filtered figures
  EXPECT_NEAR(s.first_position, 2., 1e-12);
  EXPECT_NEAR(s.last_position, 11.99, 1e-12);
}

// Window x_p in [3.995, 5.995] m: points 200..399 (x_p = 4.00 .. 5.99 m), in
// contact throughout: mean 100 N, std 20 N, 0 % without contact.
TEST(ContactForceStatistics, WindowSelectsThePantographPositions)
{
  const StatisticsParameters p;
  const auto s = evaluate_contact_force(synthetic_series(), p, {3.995, 5.995});
  const ForceFigures& r = s.raw;
  EXPECT_EQ(r.n_points, 200u);
  EXPECT_NEAR(r.mean, 100., 1e-12 * 100.);
  EXPECT_NEAR(r.std, 20., 1e-12 * 20.);
  EXPECT_EQ(r.contact_loss_percent, 0.);
  EXPECT_NEAR(s.first_position, 4., 1e-12);
  EXPECT_NEAR(s.last_position, 5.99, 1e-12);
  // A window between two time points (x_p = 4.00, 4.01 m): no point, NaN
  // figures (null in summary.json) instead of a failed run.
  const auto empty = evaluate_contact_force(synthetic_series(), p, {4.002, 4.008}).raw;
  EXPECT_EQ(empty.n_points, 0u);
  EXPECT_TRUE(std::isnan(empty.mean) && std::isnan(empty.std) && std::isnan(empty.max));
  // A window with the contact loss inside: 50 of points 50..249 = 25 %.
  EXPECT_NEAR(evaluate_contact_force(synthetic_series(), p, {2.495, 4.495})
                  .raw.contact_loss_percent,
              25., 1e-12);
}

// Filtered statistics: lambda = 100 + 10 sin(2 pi 15 t), 4 s at 2 kHz, cut-off
// 20 Hz, the default order 4: the mean stays 100 N (DC gain 1) and the std is
// that of the attenuated sine, 10 |H(15 Hz)|^2 / sqrt(2). The ends of a finite
// record (60 whole periods, odd reflection) disturb this by less than 1e-3;
// the raw figures are those of the unfiltered sine (round-off, 1e-12).
TEST(ContactForceStatistics, LowPassAttenuatesTheOscillationAnalytically)
{
  ContactForceSeries s;
  for (unsigned int n = 0; n < 8000; ++n)
  {
    s.t.push_back(n / fs);
    s.x_p.push_back(2. + 10. * s.t.back());
    s.lambda_p.push_back(100. + 10. * std::sin(2. * M_PI * 15. * s.t.back()));
    s.in_contact.push_back(true);
  }
  StatisticsParameters p;
  p.low_pass_cutoff = fc;
  const auto r = evaluate_contact_force(s, p, EvaluationWindow{});
  const double expected_std =
      10. * std::pow(ButterworthLowPass(fc, fs, 4).gain(15.), 2) / std::sqrt(2.);
  EXPECT_EQ(r.filter_cutoff_hz, fc);
  EXPECT_EQ(r.filter_order, 4u);
  ASSERT_TRUE(r.filtered.has_value());
  EXPECT_NEAR(r.filtered->mean, 100., 1e-3);
  EXPECT_NEAR(r.filtered->std / expected_std, 1., 1e-3);
  EXPECT_NEAR(r.raw.std / (10. / std::sqrt(2.)), 1., 1e-12);
}

TEST(StatisticsParameters, CutOffAboveNyquistAndEmptyWindowAreInputErrors)
{
  StatisticsParameters p;
  const std::vector<double> supports{0., 20.}; // the paper's single span
  p.low_pass_cutoff = 1e4;                     // dt = 5e-5 s: Nyquist 1e4 Hz
  EXPECT_THROW(p.check(5e-5, 2., 18., supports), InputError);
  p.low_pass_cutoff = 20.;
  EXPECT_NO_THROW(p.check(5e-5, 2., 18., supports));
  p.window = {19., 20.}; // beyond the final position
  EXPECT_THROW(p.check(5e-5, 2., 18., supports), InputError);
  p.window = {10., 5.};
  EXPECT_THROW(p.check(5e-5, 2., 18., supports), InputError);
}

// ---------------------------------------------------------------- VTU time series
namespace
{
std::string read_file(const std::string& name)
{
  std::ifstream in(name);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/**
 * The values of a DataArray of a deal.II VTU file (zlib-compressed in base64:
 * a header block, then the compressed data): the one named @p name, or the
 * point coordinates if @p name is empty.
 */
std::vector<float> data_array(const std::string& vtu, const std::string& name)
{
  const std::size_t tag = vtu.find(name.empty() ? "<Points>" : "Name=\"" + name + "\"");
  if (tag == std::string::npos)
    throw std::runtime_error("no DataArray " + name);
  const std::size_t begin = vtu.find_first_not_of(" \n\t", vtu.find('>', tag + 8) + 1);
  const std::string text = vtu.substr(begin, vtu.find_first_of(" \n\t<", begin) - begin);
  // Header: 4 uint32 (blocks = 1, block size, last size, compressed size) =
  // 16 bytes, 24 characters of base64.
  const auto header = dealii::Utilities::decode_base64(text.substr(0, 24));
  std::uint32_t h[4];
  std::memcpy(h, header.data(), 16);
  const auto compressed = dealii::Utilities::decode_base64(text.substr(24));
  std::vector<unsigned char> raw(h[1]);
  uLongf size = raw.size();
  if (uncompress(raw.data(), &size, reinterpret_cast<const Bytef*>(compressed.data()),
                 h[3]) != Z_OK)
    throw std::runtime_error("cannot inflate " + name);
  std::vector<float> values(size / sizeof(float));
  std::memcpy(values.data(), raw.data(), size);
  return values;
}

double vtu_time(const std::string& vtu)
{
  const std::size_t tag = vtu.find("Name=\"TIME\"");
  if (tag == std::string::npos)
    return std::nan("");
  return std::stod(vtu.substr(vtu.find('>', tag) + 1, 40));
}

/**
 * The 32 m/s case from x_p = 2 to 2.32 m (200 steps of 5e-5 s, t_e = 0.01 s)
 * with a frame every 2.5 ms (frames at t = 0, 2.5, 5, 7.5, 10 ms) and two
 * sample points per cell: FDM + half-explicit (the benchmark's method; its
 * multipliers lag one step) and FEM + BDF-2 (Hermite shape between nodes).
 */
void check_vtu_time_series(const SpaceMethod method, const std::string& integrator)
{
  ProgramParameters p;
  p.mode = RunMode::dynamics;
  p.scene.start = Start::paper; // the paper's case and start (13)
  p.discretisation.method = method;
  p.time_integration.integrator = integrator;
  p.pantograph().final_position = 2.32;
  const std::string dir = std::string("test_output_vtu_") + to_string(method);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  CaseRunner simulation(p.make_case(), {p.output.probe_positions, p.output.energy});
  VtuTimeSeriesWriter vtu(dir, 0.0025, p.time_integration.time_step, 2,
                          simulation.discretisation(), simulation.system());
  simulation.run({&vtu});

  // One wires file and one pantograph-droppers file per frame, nothing else.
  const unsigned int n_frames = 5;
  ASSERT_EQ(vtu.frames().size(), n_frames);
  unsigned int n_files = 0;
  for ([[maybe_unused]] const auto& f : std::filesystem::directory_iterator(dir + "/vtu"))
    ++n_files;
  EXPECT_EQ(n_files, 2 * n_frames);

  // solution.pvd lists both parts of every frame at its time; each VTU file
  // holds the same time in its TIME field (Float32: 1e-9 s).
  const std::string pvd = read_file(dir + "/solution.pvd");
  const std::regex dataset(
      "timestep=\"([^\"]+)\" group=\"\" part=\"([01])\" file=\"([^\"]+)\"");
  unsigned int listed = 0;
  for (std::sregex_iterator it(pvd.begin(), pvd.end(), dataset), end; it != end; ++it)
  {
    const double t = std::stod((*it)[1]);
    const unsigned int frame = listed / 2;
    // Frame k at the time point nearest to k * 2.5 ms (within half a step).
    EXPECT_NEAR(t, 0.0025 * frame, 0.5 * 5e-5);
    EXPECT_NEAR(vtu_time(read_file(dir + "/" + (*it)[3].str())), t, 1e-9);
    ++listed;
  }
  EXPECT_EQ(listed, 2 * n_frames);

  // First frame = the static catenary with lambda_p(0) at x_p(0), solved here
  // independently. Float32 in the file: values up to 1.1 m to 1e-6 m.
  const auto& d = simulation.discretisation();
  const SemiDiscreteSystem statics =
      build_catenary_system(d, Constraint::Kind::unilateral);
  dealii::Vector<double> load(statics.n_dofs());
  SparseRow F;
  d.load_row(p.pantograph().initial_position, 0, F);
  F.shift(statics.block("contact wire").first);
  F.add_transpose_to(load, p.pantograph().initial_contact_force);
  const auto q = solve_static_equilibrium(statics, load).q;
  const auto qc = block_values(statics, q, "carrier");
  const auto qw = block_values(statics, q, "contact wire");

  const std::string first = read_file(dir + "/vtu/wires-00000.vtu");
  const auto xyz = data_array(first, "");
  const auto w_c = data_array(first, "carrier_displacement");
  const auto w_w = data_array(first, "contact_wire_displacement");
  const auto v_c = data_array(first, "carrier_velocity");
  const auto v_w = data_array(first, "contact_wire_velocity");
  // FDM: sampled at its 501 nodes (the subdivisions are for FEM); FEM: 2 x 500
  // sample cells. Two points per sample cell.
  ASSERT_EQ(w_w.size(), method == SpaceMethod::fdm ? 1000u : 2000u);
  ASSERT_EQ(xyz.size(), 3 * w_w.size());
  double largest_sag = 0.;
  for (std::size_t i = 0; i < w_w.size(); ++i)
  {
    const double x = xyz[3 * i];
    EXPECT_NEAR(w_c[i], d.displacement(Wire::carrier, qc, x), 1e-6) << "x = " << x;
    EXPECT_NEAR(w_w[i], d.displacement(Wire::contact_wire, qw, x), 1e-6) << "x = " << x;
    // The catenary starts at rest (Sec. 2.2).
    EXPECT_EQ(v_c[i], 0.f);
    EXPECT_EQ(v_w[i], 0.f);
    largest_sag = std::max(largest_sag, -static_cast<double>(w_w[i]));
  }
  EXPECT_GT(largest_sag, 1e-3); // the comparison is not of zeros

  // The pantograph head at (x_p(0), w_p1(0)) with lambda_p(0) = 8.75 N; the
  // dropper clamps at (x_d, w_w(x_d)).
  const std::string marks = read_file(dir + "/vtu/pantograph-droppers-00000.vtu");
  const auto at = data_array(marks, "");
  const auto force = data_array(marks, "force");
  ASSERT_EQ(force.size(), 3u);
  EXPECT_NEAR(at[0], 2., 1e-6);
  EXPECT_NEAR(force[0], 8.75, 1e-5);
  EXPECT_NEAR(at[3], 5.5, 1e-6);
  EXPECT_NEAR(at[4], d.displacement(Wire::contact_wire, qw, 5.5), 1e-6);
}
} // namespace

TEST(VtuTimeSeries, FramesCarryThePhysicalTimeAndStartFromTheStaticProfileFdm)
{
  check_vtu_time_series(SpaceMethod::fdm, "half-explicit");
}

TEST(VtuTimeSeries, FramesCarryThePhysicalTimeAndStartFromTheStaticProfileFem)
{
  check_vtu_time_series(SpaceMethod::fem, "bdf2");
}

// ---------------------------------------------------------------- uplift
namespace
{
/// w_w(x_d, t) through the public displacement(), independent of the sparse rows.
struct DropperHeights : SimulationObserver
{
  DropperHeights(const CaseRunner& s) : simulation(s) {}
  void observe(const TimePoint&) override {}
  void observe_state(const TimePoint&, const DynamicState& state) override
  {
    const auto qw = block_values(simulation.system(), state.q, "contact wire");
    std::vector<double> w;
    for (const double x :
         simulation.discretisation().catenary_parameters().dropper_positions)
      w.push_back(simulation.discretisation().displacement(Wire::contact_wire, qw, x));
    heights.push_back(w);
  }
  const CaseRunner& simulation;
  std::vector<std::vector<double>> heights;
};
} // namespace

// The uplift at each dropper is max_t w_w(x_d, t) - w_w(x_d, 0): the
// observer's bookkeeping against the heights recorded here (round-off, 1e-15 m).
TEST(ContactStatistics, UpliftAtDroppersIsTheLargestRiseAboveTheStart)
{
  ProgramParameters p;
  p.mode = RunMode::dynamics;
  p.scene.start = Start::paper; // the paper's case and start (13)
  p.discretisation.method = SpaceMethod::fdm;
  p.pantograph().final_position = 6.;
  CaseRunner simulation(p.make_case(), {p.output.probe_positions, p.output.energy});
  ContactStatistics statistics(p.statistics, simulation.discretisation(),
                               simulation.system());
  DropperHeights record(simulation);
  simulation.run({&statistics, &record});
  const auto& uplift = statistics.result().max_uplift_at_droppers;
  ASSERT_EQ(uplift.size(), 2u);
  for (unsigned int j = 0; j < 2; ++j)
  {
    double largest = -1.;
    for (const auto& w : record.heights)
      largest = std::max(largest, w[j] - record.heights.front()[j]);
    EXPECT_NEAR(uplift[j], largest, 1e-15);
  }
  // The pantograph (70 N) has passed dropper 1 at 5.5 m and lifted it by
  // millimetres; dropper 2 at 14.5 m has moved less.
  EXPECT_GT(uplift[0], 1e-3);
  EXPECT_LT(uplift[1], uplift[0]);
}

// ---------------------------------------------------------------- progress
// With no delay and no rate limit: a line with percent done, simulated time,
// steps per second and time left, rewritten with a carriage return and
// erased at the end.
TEST(ProgressMeter, PrintsPercentAndTimeAndClearsTheLine)
{
  std::ostringstream out;
  ProgressMeter meter(out, 0.5, 0., 1e9);
  meter.start({});
  TimePoint point;
  point.t = 0.25;
  meter.observe(point);
  EXPECT_TRUE(meter.shown());
  EXPECT_NE(out.str().find("\r   50.0 %  t = 0.2500 s of 0.5000 s"), std::string::npos)
      << out.str();
  EXPECT_NE(out.str().find("steps/s"), std::string::npos);
  EXPECT_NE(out.str().find("s left"), std::string::npos);
  meter.finish();
  EXPECT_FALSE(meter.shown());
  EXPECT_EQ(out.str().substr(out.str().size() - 4), "\r\033[K");

  // The default delay of 1 s: a short run prints nothing at all.
  std::ostringstream quiet;
  ProgressMeter delayed(quiet, 0.5);
  delayed.start({});
  delayed.observe(point);
  delayed.finish();
  EXPECT_TRUE(quiet.str().empty());
}

// ---------------------------------------------------------------- plots

namespace
{
/// The count of values of @p xs whose write_csv_number() text differs from
/// std::to_chars's "%.10g"; the first difference goes to the test's log.
std::size_t csv_number_mismatches(const std::vector<double>& xs)
{
  std::size_t mismatches = 0;
  for (const double x : xs)
  {
    char fast[32], exact[32];
    const std::string a(fast, write_csv_number(fast, x));
    const std::string b(
        exact, std::to_chars(exact, exact + 32, x, std::chars_format::general, 10).ptr);
    if (a != b && mismatches++ == 0)
      ADD_FAILURE() << std::hexfloat << x << ": " << a << " instead of " << b;
  }
  return mismatches;
}

/// Appends @p scaled random significands in [1, 10) times 10^-30 ... 10^30
/// (alternating signs), then @p patterns random bit patterns (subnormals,
/// infinities and NaN among them) to @p xs.
void add_random_values(std::mt19937_64& random, const int scaled, const int patterns,
                       std::vector<double>& xs)
{
  std::uniform_real_distribution<double> significand(1., 10.);
  std::uniform_int_distribution<int> exponent(-30, 30);
  for (int i = 0; i < scaled; ++i)
    xs.push_back((i % 2 ? -1. : 1.) * significand(random) *
                 std::pow(10., exponent(random)));
  for (int i = 0; i < patterns; ++i)
  {
    const std::uint64_t bits = random();
    double x;
    std::memcpy(&x, &bits, sizeof x);
    xs.push_back(x);
  }
}
} // namespace

// The time series' number text is printf's "%.10g" to the character (the
// CSV of every shipped case stays the same file): random significands over
// 10^-30 ... 10^30, every bit pattern (subnormals, infinities, NaN), and
// the values next to the ties of the tenth digit, where an extended-precision
// rounding could go the wrong way (they must take the exact path).
TEST(CsvNumber, IsPrintfsTenDigitTextForEveryValue)
{
  std::mt19937_64 random(20261124);
  std::vector<double> xs;
  add_random_values(random, 600000, 200000, xs);
  std::uniform_int_distribution<int> exponent(-30, 30);
  std::uniform_int_distribution<std::uint64_t> ten_digits(1000000000ULL, 9999999999ULL);
  for (int i = 0; i < 100000; ++i)
  {
    // (n + 1/2) 10^(e - 9): a tie of the tenth digit, and its neighbours.
    double x = (static_cast<double>(ten_digits(random)) + 0.5) *
               std::pow(10., exponent(random) / 2 - 9);
    for (int k = 0; k < 3; ++k)
      x = std::nextafter(x, 0.);
    for (int k = 0; k < 7; ++k, x = std::nextafter(x, 1e300))
      xs.push_back(x);
  }
  for (int e = -25; e <= 25; ++e) // powers of ten and their neighbours
  {
    const double p = std::pow(10., e);
    xs.insert(xs.end(), {p, std::nextafter(p, 0.), std::nextafter(p, 1e300), -p,
                         9.9999999995 * p, 9.999999999 * p, 1.0000000005 * p});
  }
  xs.insert(xs.end(),
            {0., -0., 1e-5, 9.9999999995e-5, 1e-4, 9999999999.5, 1e10, 1e19, 1e-17,
             123456789012., 0.5, 2.5, std::numeric_limits<double>::min(),
             std::numeric_limits<double>::max(), std::numeric_limits<double>::infinity(),
             -std::numeric_limits<double>::infinity(),
             std::numeric_limits<double>::quiet_NaN()});
  EXPECT_EQ(csv_number_mismatches(xs), 0u) << "of " << xs.size() << " values";
}

// contact_force.csv and the plots' data blocks were written by a stream with
// precision 10; append_csv_number() writes them now and must give the same
// files to the character: 200 000 random values over 10^-30 ... 10^30, random
// bit patterns (subnormals, infinities, NaN of either sign) and the specials,
// each appended to text already there.
TEST(CsvNumber, AppendedTextIsTheStreamsAtPrecisionTen)
{
  std::mt19937_64 random(20261128);
  std::vector<double> xs = {0.,
                            -0.,
                            1e-5,
                            9.9999999995e-5,
                            1e-4,
                            9999999999.5,
                            1e10,
                            0.5,
                            2.5,
                            std::numeric_limits<double>::min(),
                            std::numeric_limits<double>::max(),
                            std::numeric_limits<double>::infinity(),
                            -std::numeric_limits<double>::infinity(),
                            std::numeric_limits<double>::quiet_NaN()};
  add_random_values(random, 200000, 20000, xs);
  std::ostringstream stream;
  stream << std::setprecision(10) << "t,x";
  std::string appended = "t,x";
  for (const double x : xs)
  {
    stream << ',' << x;
    appended += ',';
    append_csv_number(appended, x);
  }
  const std::string streamed = stream.str();
  EXPECT_TRUE(streamed == appended)
      << "the first difference at character "
      << std::mismatch(appended.begin(), appended.end(), streamed.begin(), streamed.end())
                 .first -
             appended.begin();
}

TEST(PlotData, EnvelopeKeepsEveryBinsExtremesInOrderAndTheEnds)
{
  // A fast oscillation under a slow one, 100 000 points over [0, 1]: with 200
  // bins the envelope keeps, per bin, the lowest and the highest point of the
  // curve (found here by brute force), in their order, and the first and last
  // point; nothing else.
  const unsigned int n = 100000, bins = 200;
  std::vector<double> x(n), y(n);
  for (unsigned int i = 0; i < n; ++i)
  {
    x[i] = i / (n - 1.);
    y[i] = std::sin(6.3 * x[i]) + 0.3 * std::sin(4000. * x[i] + 0.1 * (i % 7));
  }
  const PlotCurve c = envelope(x, y, bins);
  ASSERT_LE(c.x.size(), 2 * bins + 2);
  EXPECT_EQ(c.x.front(), x.front());
  EXPECT_EQ(c.x.back(), x.back());
  for (std::size_t k = 1; k < c.x.size(); ++k)
    ASSERT_LT(c.x[k - 1], c.x[k]) << "point " << k; // in the order they come
  for (unsigned int b = 0; b < bins; ++b)
  {
    double low = 1e300, high = -1e300, kept_low = 1e300, kept_high = -1e300;
    for (unsigned int i = 0; i < n; ++i)
      if (std::min<unsigned int>(bins - 1, x[i] * bins) == b)
      {
        low = std::min(low, y[i]);
        high = std::max(high, y[i]);
      }
    for (std::size_t k = 0; k < c.x.size(); ++k)
      if (std::min<unsigned int>(bins - 1, c.x[k] * bins) == b)
      {
        kept_low = std::min(kept_low, c.y[k]);
        kept_high = std::max(kept_high, c.y[k]);
      }
    ASSERT_EQ(kept_low, low) << "bin " << b;
    ASSERT_EQ(kept_high, high) << "bin " << b;
  }
  // Short curves pass unchanged; points that are not finite are left out.
  const PlotCurve s = envelope({0., 1., 2.}, {5., std::nan(""), 7.}, bins);
  EXPECT_EQ(s.x, (std::vector<double>{0., 2.}));
  EXPECT_EQ(s.y, (std::vector<double>{5., 7.}));
}

TEST(PlotData, CsvColumnsAreReadByPlaceInTheOrderAsked)
{
  const std::string path = "plot_data_columns.csv";
  {
    std::ofstream csv(path);
    csv << "t,a,b,c\n0,1.5,-2e-3,7\n0.25,2.5,nan,8\n";
  }
  const auto columns = read_csv_columns(path, {4, 1, 2});
  ASSERT_EQ(columns.size(), 3u);
  EXPECT_EQ(columns[0], (std::vector<double>{7., 8.}));
  EXPECT_EQ(columns[1], (std::vector<double>{0., 0.25}));
  EXPECT_EQ(columns[2], (std::vector<double>{1.5, 2.5}));
  EXPECT_EQ(read_csv_columns(path, {3})[0][0], -2e-3);
  EXPECT_TRUE(std::isnan(read_csv_columns(path, {3})[0][1]));
  EXPECT_THROW(read_csv_columns(path, {5}), SimulationError);
  std::filesystem::remove(path);
}
