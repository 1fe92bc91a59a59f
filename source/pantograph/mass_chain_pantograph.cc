#include <pantocat/base/input_error.h>
#include <pantocat/pantograph/mass_chain_pantograph.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <algorithm>

namespace pantocat
{
MassChainPantograph::MassChainPantograph(const MassChainPantographParameters& parameters,
                                         const double speed)
    : p(parameters), aerodynamic_force(parameters.aerodynamic_force(speed))
{
  p.check("Pantograph/Mass-chain model");
}

std::vector<std::string> MassChainPantograph::coordinate_names() const
{
  std::vector<std::string> names;
  for (unsigned int i = 1; i <= p.n_bodies(); ++i)
    names.push_back("w_p" + std::to_string(i));
  return names;
}

double MassChainPantograph::static_force() const
{
  return p.static_force + aerodynamic_force;
}

dealii::Vector<double> MassChainPantograph::constant_load() const
{
  dealii::Vector<double> f(p.n_bodies());
  const unsigned int j = p.uplift_body() - 1;
  if (p.reference == ChainReference::relaxed_springs)
    f(j) = p.static_force + aerodynamic_force;
  else
  {
    f(0) = p.static_force;
    f(j) += aerodynamic_force;
  }
  return f;
}

void MassChainPantograph::assemble(BlockOperator& op) const
{
  const unsigned int n = p.n_bodies();
  op.name = "pantograph";
  dealii::DynamicSparsityPattern dsp(n, n);
  for (unsigned int i = 0; i < n; ++i)
    for (unsigned int j = (i > 0 ? i - 1 : 0); j <= std::min(n - 1, i + 1); ++j)
      dsp.add(i, j);
  op.sparsity->copy_from(dsp);
  op.reinit_matrices(n);
  op.mass_is_diagonal = true;
  // Without every spring only the contact holds the bodies.
  op.stiffness_is_definite = std::all_of(p.stiffnesses.begin(), p.stiffnesses.end(),
                                         [](double k) { return k > 0.; });
  for (unsigned int i = 0; i < n; ++i)
    op.mass.set(i, i, p.masses[i]);
  // Link i joins bodies i and i + 1 (0-based, i < n - 1); link n - 1 the frame
  // and the ground.
  const auto link =
      [](dealii::SparseMatrix<double>& matrix, const unsigned int i, const double value)
  {
    matrix.add(i, i, value);
    matrix.add(i + 1, i + 1, value);
    matrix.add(i, i + 1, -value);
    matrix.add(i + 1, i, -value);
  };
  for (unsigned int i = 0; i + 1 < n; ++i)
  {
    link(op.stiffness, i, p.stiffnesses[i]);
    link(op.damping, i, p.dampings[i]);
  }
  op.stiffness.add(n - 1, n - 1, p.stiffnesses[n - 1]);
  op.damping.add(n - 1, n - 1, p.dampings[n - 1]);
  op.load = constant_load();
}

SparseRow MassChainPantograph::head_row() const
{
  SparseRow B;
  B.add(0, 1.);
  return B;
}

void MassChainPantograph::consistent_state(const double head_position,
                                           const double head_velocity,
                                           const double head_acceleration,
                                           const double contact_force,
                                           const double offset, dealii::Vector<double>& q,
                                           dealii::Vector<double>& v) const
{
  const unsigned int n = p.n_bodies();
  const dealii::Vector<double> f = constant_load();
  const auto& k = p.stiffnesses;
  const auto& c = p.dampings;
  q.reinit(n);
  v.reinit(n);
  q(0) = head_position;
  v(0) = head_velocity;
  if (p.start == ChainStart::static_equilibrium)
  {
    // T_i: the force of link i upwards on body i (downwards on body i + 1).
    double T = p.masses[0] * head_acceleration - f(0) + contact_force;
    for (unsigned int i = 0; i + 1 < n; ++i)
    {
      q(i + 1) = q(i) + (k[i] > 0. ? T / k[i] : 0.);
      v(i + 1) = v(i) + (k[i] > 0. ? 0. : T / c[i]);
      T -= f(i + 1);
    }
    return;
  }
  // Offset (13), as TwoMassPantograph and ThreeMassPantograph (same operations,
  // so that the same data give the same numbers).
  q(1) = head_position - offset;
  v(1) = head_velocity +
         (p.masses[0] * head_acceleration + k[0] * offset + contact_force - f(0)) / c[0];
  // Bodies 3..n: K_rr w_r = f_r + k_2 w_2 e_3 (Thomas algorithm on the
  // tridiagonal block of the bodies below body 2).
  if (n < 3)
    return;
  const unsigned int r = n - 2;
  std::vector<double> diagonal(r), rhs(r);
  for (unsigned int i = 0; i < r; ++i)
  {
    const unsigned int b = i + 2;
    diagonal[i] = k[b - 1] + k[b];
    rhs[i] = f(b);
  }
  rhs[0] = f(2) - (-k[1]) * q(1);
  const auto require_pivot = [&](const double pivot)
  {
    require(pivot > 0., "Pantograph/Mass-chain model/Initial configuration", "offset",
            "balances bodies 3..n by their springs, which vanish below body 2; "
            "allowed: static equilibrium, or springs k_2..k_n that hold those bodies");
  };
  for (unsigned int i = 1; i < r; ++i)
  {
    require_pivot(diagonal[i - 1]);
    const double factor = -k[i + 1] / diagonal[i - 1];
    diagonal[i] -= factor * -k[i + 1];
    rhs[i] -= factor * rhs[i - 1];
  }
  require_pivot(diagonal[r - 1]);
  q(n - 1) = rhs[r - 1] / diagonal[r - 1];
  for (unsigned int i = r - 1; i-- > 0;)
    q(i + 2) = (rhs[i] - (-k[i + 2]) * q(i + 3)) / diagonal[i];
  for (unsigned int i = 2; i < n; ++i)
    v(i) = head_velocity;
}
} // namespace pantocat
