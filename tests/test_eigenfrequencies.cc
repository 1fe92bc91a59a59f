// Eigenfrequencies: Table 1 of the paper, closed forms of the discrete string
// and beam, and the h^4 convergence of Hermite beam eigenvalues.
#include <pantocat/analysis/banded_eigenvalues.h>
#include <pantocat/analysis/eigenfrequency_analysis.h>
#include <pantocat/space/catenary_discretisation.h>

#include <deal.II/base/numbers.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace pantocat;

namespace
{
const double pi = dealii::numbers::PI;

std::vector<SubsystemFrequencies> table1(SpaceMethod method, unsigned int n = 500)
{
  DiscretisationParameters d;
  d.method = method;
  d.n_intervals = n;
  return compute_extreme_frequencies(
      *create_catenary_discretisation(CatenaryParameters(), d));
}

/// |value - paper| <= half a unit in the paper's 5th significant digit.
double half_unit_of_5th_digit(double paper)
{
  return 0.5 * std::pow(10., std::floor(std::log10(paper)) - 4);
}
} // namespace

TEST(Table1, SevenOfEightNumbersToThePapersFiveDigits)
{
  for (const SpaceMethod method : {SpaceMethod::fem, SpaceMethod::fdm})
    for (const auto& f : table1(method))
    {
      const double paper_max = PaperTable1::f_max(f.discretisation, f.subsystem);
      EXPECT_NEAR(f.f_max_hz, paper_max, half_unit_of_5th_digit(paper_max))
          << f.discretisation << ' ' << f.subsystem;
      const double paper_min = PaperTable1::f_min(f.discretisation, f.subsystem);
      if (f.discretisation == "fem" && f.subsystem == "carrier")
        continue; // see the next test
      EXPECT_NEAR(f.f_min_hz, paper_min, half_unit_of_5th_digit(paper_min))
          << f.discretisation << ' ' << f.subsystem;
    }
}

TEST(Table1, FemCarrierLowestFrequencyIsTheClosedFormAndWithinOneUnitOfThePaper)
{
  // Linear elements with consistent mass have the exact discrete spectrum
  // omega^2 = (6 c^2/h^2) (1 - cos kh) / (2 + cos kh), k = pi/L. At N+1 = 500
  // this is f = 3.9528536 Hz, which rounds to 3.9529; the paper prints 3.9528
  // (6-digit 3.95285 rounded half-to-even). We assert the closed form to 1e-9
  // and the paper to one unit in its last digit. doc/formulation.md explains.
  const auto f = table1(SpaceMethod::fem)[0];
  const CatenaryParameters p;
  const double c = p.carrier.wave_speed(), h = p.span / 500., kh = pi / p.span * h;
  const double omega =
      std::sqrt(6. * c * c / (h * h) * (1. - std::cos(kh)) / (2. + std::cos(kh)));
  EXPECT_NEAR(f.f_min_hz, omega / (2. * pi), 1e-9 * f.f_min_hz);
  EXPECT_NEAR(f.f_min_hz, 3.9528, 1e-4);
}

TEST(Table1, StepSizeLimitsOfTheHalfExplicitMethod)
{
  // Sec. 6: 6.6e-5 s (FDM) and 5.3e-6 s (FEM), printed by the paper with two
  // digits (truncated: 2/omega_max = 6.62e-5 and 5.37e-6).
  EXPECT_NEAR(explicit_step_size_limit(table1(SpaceMethod::fdm)), 6.62e-5, 0.5e-7);
  EXPECT_NEAR(explicit_step_size_limit(table1(SpaceMethod::fem)), 5.37e-6, 0.5e-8);
}

TEST(Spectrum, FdmStringAndBeamMatchTheirDiscreteClosedForms)
{
  // FDM eigenvectors are sin(k pi x/L): omega_k^2 = (4 T s^2/h^2 + 16 EI s^4/h^4)/rhoA,
  // s = sin(k pi h / (2L)). Lowest (k = 1) and highest (k = N) to 1e-10.
  const CatenaryParameters p;
  const unsigned int n = 100;
  const double h = p.span / n;
  const auto f = table1(SpaceMethod::fdm, n);
  for (unsigned int w = 0; w < 2; ++w)
  {
    const WireParameters& wire = w == 0 ? p.carrier : p.contact_wire;
    for (const unsigned int k : {1u, n - 1})
    {
      const double s = std::sin(k * pi * h / (2. * p.span));
      const double omega2 =
          (4. * wire.tension * s * s / (h * h) +
           16. * wire.bending_stiffness * std::pow(s, 4) / std::pow(h, 4)) /
          wire.mass_per_length;
      const double expected = std::sqrt(omega2) / (2. * pi);
      EXPECT_NEAR(k == 1 ? f[w].f_min_hz : f[w].f_max_hz, expected, 1e-10 * expected);
    }
  }
}

TEST(Spectrum, FemLowestFrequenciesConvergeToTheContinuousString)
{
  // String: f_1 = c / (2L). Beam (simply supported, tensioned):
  // omega_1^2 = (EI k^4 + T k^2) / rhoA, k = pi/L. Both within 2e-6 relative at
  // N+1 = 500 (the FEM error is O(h^2) for the string, (kh)^2/24 = 1.6e-6).
  const CatenaryParameters p;
  const auto f = table1(SpaceMethod::fem);
  const double k = pi / p.span;
  EXPECT_NEAR(f[0].f_min_hz, p.carrier.wave_speed() / (2. * p.span),
              2e-6 * f[0].f_min_hz);
  const auto& w = p.contact_wire;
  const double beam =
      std::sqrt((w.bending_stiffness * std::pow(k, 4) + w.tension * k * k) /
                w.mass_per_length) /
      (2. * pi);
  EXPECT_NEAR(f[1].f_min_hz, beam, 1e-9 * beam); // cubic elements: O(h^4)
}

TEST(Spectrum, HermiteBeamEigenvaluesConvergeWithOrderFour)
{
  // Pure beam (T -> tiny): lambda_1 = EI k^4 / rhoA. Conforming cubic elements
  // for a 4th-order operator: eigenvalue error O(h^{2(p+1-m)}) = O(h^4).
  CatenaryParameters p;
  p.contact_wire.tension = 1e-9;
  const double k = pi / p.span;
  const double exact =
      p.contact_wire.bending_stiffness * std::pow(k, 4) / p.contact_wire.mass_per_length;
  std::vector<double> errors;
  for (const unsigned int n : {4u, 8u, 16u, 32u})
  {
    DiscretisationParameters d;
    d.n_intervals = n;
    BlockOperator op;
    create_catenary_discretisation(p, d)->assemble(Wire::contact_wire, op);
    errors.push_back(smallest_generalized_eigenvalue(op.stiffness, op.mass) / exact - 1.);
  }
  for (unsigned int i = 1; i < errors.size(); ++i)
  {
    const double order = std::log2(errors[i - 1] / errors[i]);
    EXPECT_NEAR(order, 4., 0.1) << "refinement " << i;
  }
}

TEST(Spectrum, LinearStringEigenvaluesConvergeWithOrderTwo)
{
  CatenaryParameters p;
  const double k = pi / p.span;
  const double exact = p.carrier.tension * k * k / p.carrier.mass_per_length;
  std::vector<double> errors;
  for (const unsigned int n : {8u, 16u, 32u, 64u})
  {
    DiscretisationParameters d;
    d.n_intervals = n;
    BlockOperator op;
    create_catenary_discretisation(p, d)->assemble(Wire::carrier, op);
    errors.push_back(smallest_generalized_eigenvalue(op.stiffness, op.mass) / exact - 1.);
  }
  for (unsigned int i = 1; i < errors.size(); ++i)
    EXPECT_NEAR(std::log2(errors[i - 1] / errors[i]), 2., 0.05) << "refinement " << i;
}

TEST(Spectrum, LargestStringEigenvalueByBisectionIsTheClosedForm)
{
  // The top of the closed-form spectrum of the linear string (above): mode
  // N - 1 of N intervals, omega^2 = (6 c^2/h^2) (1 - cos kh) / (2 + cos kh),
  // kh = (N - 1) pi / N. The bisection stops between neighbouring doubles;
  // what is left is round-off of the assembly and of the factorisations.
  CatenaryParameters p;
  const unsigned int n = 500;
  DiscretisationParameters d;
  d.n_intervals = n;
  BlockOperator op;
  create_catenary_discretisation(p, d)->assemble(Wire::carrier, op);
  const double c = p.carrier.wave_speed(), h = p.span / n, kh = (n - 1.) * pi / n;
  const double exact = 6. * c * c / (h * h) * (1. - std::cos(kh)) / (2. + std::cos(kh));
  EXPECT_NEAR(largest_generalized_eigenvalue(op.stiffness, op.mass) / exact, 1., 1e-13);
}

TEST(Spectrum, LargestBeamEigenvalueByBisectionAgreesWithTheTridiagonalReduction)
{
  // The Hermite contact wire (half bandwidth 3) has no closed form; LAPACK's
  // dsbgvx (reduction to tridiagonal form) gives its largest eigenvalue to full
  // relative accuracy as 1 / smallest eigenvalue of the swapped pencil. Both
  // are exact to round-off times a modest factor: 1e-13 relative.
  CatenaryParameters p;
  DiscretisationParameters d;
  d.n_intervals = 500;
  BlockOperator op;
  create_catenary_discretisation(p, d)->assemble(Wire::contact_wire, op);
  const double by_reduction = 1. / smallest_generalized_eigenvalue(op.mass, op.stiffness);
  EXPECT_NEAR(largest_generalized_eigenvalue(op.stiffness, op.mass) / by_reduction, 1.,
              1e-13);
}
