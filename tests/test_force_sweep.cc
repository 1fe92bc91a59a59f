// The right-hand side f - K q - D (v_{n-1} + v_n)/2 of the half-explicit step
// from stored diagonals: on runs of rows whose coefficients repeat with
// period 2 it reads them kept aside, elsewhere from the diagonals; both give
// the row's terms in the same order, so the result is the same to the bit.
#include <pantocat/lac/diagonal_force_sweep.h>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace pantocat;

TEST(ForceSweep, RunsAndDiagonalsGiveEachRowToTheBit)
{
  // 1300 rows, half bandwidth 3, seven stiffness and seven damping offsets.
  // The coefficients repeat with period 2 (a Hermite beam's displacement and
  // rotation rows) except rows 100 and 101 (a point mass), rows 600 to 611
  // (more than eight in a row: a run ends there) and the first and last
  // three (the ends). Each row of the sweep must equal the row summed here
  // term by term in the offsets' order (EXPECT_EQ: bit for bit), and the
  // rows from kept coefficients must be those of the runs [3, 600), with
  // rows 100 and 101 as its exceptions, and [612, 1297): 1280 rows. The
  // first run is longer than a block of 512 rows.
  const int n = 1300, b = 3;
  std::vector<int> offsets = {-3, -2, -1, 0, 1, 2, 3};
  std::vector<std::vector<double>> k(2 * b + 1, std::vector<double>(n, 0.)),
      d(2 * b + 1, std::vector<double>(n, 0.));
  for (const int o : offsets)
    for (int i = 0; i < n; ++i)
    {
      if (i + o < 0 || i + o >= n)
        continue;
      const int parity = i % 2;
      const bool special =
          i == 100 || i == 101 || (i >= 600 && i < 612) || i < 3 || i >= n - 3;
      const double extra = special ? 0.37 * (i % 7 + 1) : 0.;
      k[o + b][i] = (o == 0 ? 4.1 : -1.3 / (std::abs(o) + parity)) + extra;
      d[o + b][i] = 0.01 * (o == 0 ? 2.2 : 0.3 / (std::abs(o) + 2 * parity)) + extra;
    }
  DiagonalForceSweep sweep;
  sweep.initialize(n, b, offsets, k, offsets, d);
  EXPECT_EQ(sweep.rows_in_runs(), (600 - 3 - 2) + (1297 - 612));

  std::vector<double> f(n), q(n), vp(n), v(n), out(n);
  for (int i = 0; i < n; ++i)
  {
    f[i] = std::sin(0.1 * i);
    q[i] = std::cos(0.37 * i) * 1e-2;
    vp[i] = std::sin(0.71 * i + 1.);
    v[i] = std::cos(0.29 * i - 2.);
  }
  sweep.apply(f.data(), q.data(), vp.data(), v.data(), out.data());
  for (int i = 0; i < n; ++i)
  {
    double s = f[i];
    for (const int o : offsets)
      if (i + o >= 0 && i + o < n)
        s -= k[o + b][i] * q[i + o];
    for (const int o : offsets)
      if (i + o >= 0 && i + o < n)
        s -= d[o + b][i] * (vp[i + o] + v[i + o]);
    EXPECT_EQ(out[i], s) << "row " << i;
  }
}
