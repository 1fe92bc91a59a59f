// The constrained linear algebra under the integrators (ConstrainedOperator):
// each implementation satisfies the equations that define its operations
// (A^-1, the known part of an implicit step, the multiplier system of one
// level and the columns A^-1 G^T y) to round-off, on the paper's system with
// rigid and with compliant constraints, FDM and FEM; and the fast
// implementation equals the reference one, its oracle.
#include <pantocat/app/program_parameters.h>
#include <pantocat/base/input_error.h>
#include <pantocat/constrained/constrained_operator.h>
#include <pantocat/simulation/case_runner.h>
#include <pantocat/time/constraint_evaluator.h>

#include "support/case_files.h"

#include <gtest/gtest.h>

#include <random>

using namespace pantocat;

namespace
{
/// The 32 m/s benchmark on a coarse grid: rigid unilateral droppers and
/// contact, or elastic droppers (fixed compliant rows) and a damped penalty
/// contact (a moving compliant row with a rate weight).
ProgramParameters benchmark(const std::string& method, const bool compliant)
{
  std::vector<std::string> overrides = {"Discretisation/Method=" + method,
                                        "Discretisation/Number of intervals=100"};
  if (compliant)
    for (const char* s : {"Scene/Droppers=elastic", "Scene/Contact=penalty",
                          "Scene/Contact damping=40"})
      overrides.push_back(s);
  return read_case(source_file("prm/benchmark-32.prm"), overrides);
}

/// The operators a method writes: M, M + dt/2 D, S = K + c_v D + c_q M (the
/// generalized-alpha factors of rho_inf = 0.5, dt = 5e-5 s), with the
/// compliance 1/(k (1 + d c_v)) and rate weight d/(1 + d c_v) of each
/// compliant constraint (d = c/k) on S.
std::vector<ConstrainedOperator::Definition> operators(const SemiDiscreteSystem& system)
{
  const double h = 5e-5, c_v = 2.4 / h, c_q = 1.92 / (h * h);
  ConstrainedOperator::Definition M, half, S;
  M.what = "M";
  half.damping = h / 2.;
  half.what = "M + dt/2 D";
  S.mass = c_q;
  S.damping = c_v;
  S.stiffness = 1.;
  S.what = "S";
  for (const auto& c : system.constraints)
  {
    const double k = c->compliance().stiffness,
                 d = c->is_compliant() ? c->compliance().damping / k : 0.;
    S.compliance.push_back(c->is_compliant() ? 1. / (k * (1. + d * c_v)) : 0.);
    S.rate_weight.push_back(d / (1. + d * c_v));
  }
  return {M, half, S};
}

dealii::Vector<double> random_vector(const unsigned int n, std::mt19937& generator)
{
  std::uniform_real_distribution<double> u(-1., 1.);
  dealii::Vector<double> x(n);
  for (double& value : x)
    value = u(generator);
  return x;
}

/// A x for A = c_M M + c_D D + c_K K.
dealii::Vector<double> apply(const SemiDiscreteSystem& system,
                             const ConstrainedOperator::Definition& d,
                             const dealii::Vector<double>& x)
{
  dealii::Vector<double> y(x.size()), w(x.size());
  system.mass.vmult(w, x);
  y.add(d.mass, w);
  system.damping.vmult(w, x);
  y.add(d.damping, w);
  system.stiffness.vmult(w, x);
  y.add(d.stiffness, w);
  return y;
}

/// The results of one implementation on one operator, for the comparison.
struct Results
{
  dealii::Vector<double> inverse, history, columns;
  std::vector<double> multipliers;
};

/**
 * Each operation of @p op on A = @p d against its defining equation, with
 * the rows at t = 0.1 s (the contact between droppers 2 and 3): the relative
 * residuals below 1e-11 (round-off of a direct solve of a matrix of
 * condition <= 1e5, and of the small dense system).
 */
Results check_operations(const SemiDiscreteSystem& system,
                         const ConstrainedOperator::Definition& d,
                         const LinearAlgebra algebra, const std::string& label)
{
  SCOPED_TRACE(label + ", " + to_string(algebra));
  std::unique_ptr<ConstrainedOperator> A = make_constrained_operator(system, d, algebra);
  ConstraintEvaluator evaluator(system);
  const double t = 0.1;
  const std::vector<ConstraintState>& rows = evaluator.at(t, 1);
  A->set_rows(rows, t);
  const unsigned int n = system.n_dofs(), m = system.n_constraints();
  std::mt19937 generator(7);
  Results out;

  // A^-1: A (A^-1 b) = b.
  const dealii::Vector<double> b = random_vector(n, generator);
  out.inverse = b;
  A->apply_inverse(out.inverse);
  dealii::Vector<double> residual = apply(system, d, out.inverse);
  residual -= b;
  EXPECT_LT(residual.l2_norm(), 1e-11 * b.l2_norm());

  // The known part of an implicit step: A x = f(t) + M h + D r.
  const dealii::Vector<double> h = random_vector(n, generator),
                               r = random_vector(n, generator);
  A->solve_history(t, h, r, out.history);
  dealii::Vector<double> known(n), w(n);
  system.load_at(t, known);
  system.mass.vmult(w, h);
  known += w;
  system.damping.vmult(w, r);
  known += w;
  residual = apply(system, d, out.history);
  residual -= known;
  EXPECT_LT(residual.l2_norm(), 1e-11 * known.l2_norm());

  // The multiplier system on every constraint: (G_i + e_i G_t,i) A^-1 G^T y
  // + C_i y_i = r_i, with A (A^-1 G^T y) = G^T y.
  std::vector<unsigned int> all(m);
  std::vector<double> rhs(m);
  for (unsigned int i = 0; i < m; ++i)
  {
    all[i] = i;
    rhs[i] = std::uniform_real_distribution<double>(-1e-3, 1e-3)(generator);
  }
  out.multipliers = rhs;
  A->solve_multipliers(all, out.multipliers, "test");
  out.columns.reinit(n);
  A->add_columns(out.multipliers, out.columns);
  dealii::Vector<double> force(n);
  for (unsigned int i = 0; i < m; ++i)
    rows[i].G.add_transpose_to(force, out.multipliers[i]);
  residual = apply(system, d, out.columns);
  residual -= force;
  EXPECT_LT(residual.l2_norm(), 1e-11 * force.l2_norm());
  double worst = 0., scale = 0.;
  for (unsigned int i = 0; i < m; ++i)
  {
    const double e = d.rate_weight.empty() ? 0. : d.rate_weight[i],
                 C = d.compliance.empty() ? 0. : d.compliance[i];
    const double lhs = rows[i].G.dot(out.columns) + e * rows[i].G_t.dot(out.columns) +
                       C * out.multipliers[i];
    worst = std::max(worst, std::abs(lhs - rhs[i]));
    scale = std::max(scale, std::abs(rhs[i]));
  }
  EXPECT_LT(worst, 1e-11 * scale);
  return out;
}

double relative_difference(const dealii::Vector<double>& a, const dealii::Vector<double>& b)
{
  dealii::Vector<double> d(a);
  d -= b;
  return d.linfty_norm() / b.linfty_norm();
}

double relative_difference(const std::vector<double>& a, const std::vector<double>& b)
{
  double worst = 0., scale = 0.;
  for (unsigned int i = 0; i < a.size(); ++i)
  {
    worst = std::max(worst, std::abs(a[i] - b[i]));
    scale = std::max(scale, std::abs(b[i]));
  }
  return worst / scale;
}

void check_fast_against_reference(const std::string& method, const bool compliant)
{
  const CaseRunner runner(benchmark(method, compliant).make_case());
  const SemiDiscreteSystem& system = runner.system();
  ASSERT_GT(system.n_constraints(), 2u);
  for (const ConstrainedOperator::Definition& d : operators(system))
  {
    const std::string label = method + (compliant ? " compliant " : " rigid ") + d.what;
    const Results fast = check_operations(system, d, LinearAlgebra::fast, label);
    const Results reference = check_operations(system, d, LinearAlgebra::reference, label);
    SCOPED_TRACE(label);
    // The oracle: the same numbers up to round-off and the fast one's
    // truncations (columns below 1e-16 of their largest entry, Schur entries
    // below 1e-15 of their diagonal).
    EXPECT_LT(relative_difference(fast.inverse, reference.inverse), 1e-11);
    EXPECT_LT(relative_difference(fast.history, reference.history), 1e-11);
    EXPECT_LT(relative_difference(fast.multipliers, reference.multipliers), 1e-10);
    EXPECT_LT(relative_difference(fast.columns, reference.columns), 1e-10);
  }
}
} // namespace

TEST(ConstrainedOperator, FdmRigidConstraintsFastEqualsReference)
{
  check_fast_against_reference("fdm", false);
}

TEST(ConstrainedOperator, FemRigidConstraintsFastEqualsReference)
{
  check_fast_against_reference("fem", false);
}

TEST(ConstrainedOperator, FdmCompliantConstraintsFastEqualsReference)
{
  check_fast_against_reference("fdm", true);
}

TEST(ConstrainedOperator, FemCompliantConstraintsFastEqualsReference)
{
  check_fast_against_reference("fem", true);
}

TEST(ConstrainedOperator, ProjectionMeetsTheLevelAndAnEmptySetChangesNothing)
{
  // x onto g = 0 of droppers 1 and 2 (rigid, M): afterwards G_i x + z_i = 0
  // to round-off (1e-14 m against gaps of 1e-2 m), the other constraints'
  // multipliers 0; an empty set leaves x as it was, bit for bit.
  const CaseRunner runner(benchmark("fem", false).make_case());
  const SemiDiscreteSystem& system = runner.system();
  for (const LinearAlgebra algebra : {LinearAlgebra::fast, LinearAlgebra::reference})
  {
    SCOPED_TRACE(to_string(algebra));
    std::unique_ptr<ConstrainedOperator> M =
        make_constrained_operator(system, {}, algebra);
    ConstraintEvaluator evaluator(system);
    const std::vector<ConstraintState>& rows = evaluator.at(0.05, 1);
    M->set_rows(rows, 0.05);
    std::mt19937 generator(3);
    dealii::Vector<double> q = random_vector(system.n_dofs(), generator);
    q *= 1e-2;
    std::vector<double> mu;
    const auto gap = [&](const unsigned int i) { return rows[i].position_residual(q); };
    M->project({0, 1}, gap, q, mu, "test projection");
    EXPECT_LT(std::abs(gap(0)), 1e-14);
    EXPECT_LT(std::abs(gap(1)), 1e-14);
    for (unsigned int i = 2; i < system.n_constraints(); ++i)
      EXPECT_EQ(mu[i], 0.);
    const dealii::Vector<double> before = q;
    M->project({}, gap, q, mu, "test projection");
    EXPECT_EQ(relative_difference(q, before), 0.);
  }
}
