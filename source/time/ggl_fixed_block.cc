#include <pantocat/time/active_set.h>
#include <pantocat/time/ggl_fixed_block.h>

#include <algorithm>
#include <cmath>

namespace pantocat
{
void GglFixedBlock::initialize(const std::vector<const SparseRow*>& G,
                               const std::vector<const Constraint*>& constraints,
                               const SparseDirectSolver& S, const MassInverse& M,
                               const dealii::SparseMatrix<double>& D, const double c_,
                               const unsigned int n_dofs)
{
  m = G.size();
  c = c_;
  ratio.assign(m, 0.);
  std::vector<double> compliance(m, 0.);
  for (unsigned int k = 0; k < m; ++k)
  {
    ratio[k] = pantocat::damping_ratio(*constraints[k]);
    if (constraints[k]->is_compliant())
      compliance[k] = 1. / (constraints[k]->compliance().stiffness * (1. + ratio[k] * c));
  }
  P.initialize(G, FixedConstraintSchur::column_solver(S, true), n_dofs,
               "matrix G S^-1 G^T + C of the fixed constraints (BDF)", compliance);
  N.initialize(G, FixedConstraintSchur::column_solver(M, true), n_dofs,
               "matrix G M^-1 G^T of the fixed constraints (BDF)", {});
  Y.initialize(N.truncated_columns(), n_dofs);

  // Q_kl = G_k S^-1 (c G_l^T + D M^-1 G_l^T), and those columns.
  std::vector<SparseRow> mu_columns;
  std::vector<SparseRow> Q_rows(m);
  dealii::Vector<double> y(n_dofs), x(n_dofs);
  for (unsigned int l = 0; l < m; ++l)
  {
    y = 0.;
    G[l]->add_transpose_to(y, 1.);
    M.apply(y);
    D.vmult(x, y);
    G[l]->add_transpose_to(x, c);
    S.solve(x);
    mu_columns.push_back(truncated(x));
    std::vector<double> column(m);
    double largest = 0.;
    for (unsigned int k = 0; k < m; ++k)
    {
      column[k] = G[k]->dot(x);
      largest = std::max(largest, std::abs(column[k]));
    }
    for (unsigned int k = 0; k < m; ++k)
      if (std::abs(column[k]) > 1e-15 * largest)
        Q_rows[k].add(l, column[k]);
  }
  X.initialize(P.truncated_columns(), n_dofs, mu_columns);
  Q.clear();
  for (const SparseRow& row : Q_rows)
    Q.push_back(row);
  P_eta.reinit(m);
  Q_mu.reinit(m);
  N_mu.reinit(m);
  force_set.assign(m, false);
  engaged_set.assign(m, false);

  rows.clear();
  for (const SparseRow* g : G)
    rows.push_back(*g);
  S_inverse = &S;
  M_inverse = &M;
  damping = &D;
  // Columns: a pass over the slices of X (X^lambda and X^mu side by side) and
  // of Y (two sums), four unknowns per multiply-add; solves: S once, M once
  // for two right-hand sides, D once, one multiply-add per entry of their
  // factors, in chains that wait on each other. A slice's multiply-add costs
  // about 1/2.5 of a substitution's (bench_constraints, FEM + BDF-2, h = 0.2
  // m: the columns were faster at m = 100, 200 and 400, by 30 %, 17 % and 5 %).
  const SparseDirectSolver* M_factor = M.factorised();
  const double solve_cost = S.solve_cost() +
                            (M_factor ? M_factor->solve_cost() : n_dofs) +
                            D.n_nonzero_elements();
  const double columns_cost =
      static_cast<double>(X.n_slice_operations() + 2 * Y.n_slice_operations()) / 2.5;
  solves_are_cheaper = columns_cost > solve_cost;
  if (solves_are_cheaper)
  {
    mass_batch.reinit(n_dofs);
    work.reinit(n_dofs);
    D_y.reinit(n_dofs);
  }
}

void GglFixedBlock::add_forces(const std::vector<double>& lambda_plus_eta,
                               const std::vector<double>& eta,
                               const std::vector<double>& mu, dealii::Vector<double>& q,
                               dealii::Vector<double>& u1,
                               dealii::Vector<double>& u2) const
{
  if (!solves_are_cheaper)
  {
    X.add_with_partners(lambda_plus_eta, mu, q);
    Y.add(mu, u1, eta, u2);
    return;
  }
  const unsigned int n = q.size();
  mass_batch.clear();
  for (unsigned int k = 0; k < m; ++k)
  {
    mass_batch.add_row(0, rows[k], mu[k]);
    mass_batch.add_row(1, rows[k], eta[k]);
    rows[k].add_transpose_to(work, lambda_plus_eta[k] + c * mu[k]);
  }
  M_inverse->apply(mass_batch);
  for (unsigned int i = 0; i < n; ++i)
  {
    u1[i] += mass_batch(i, 0);
    u2[i] += mass_batch(i, 1);
    D_y[i] = mass_batch(i, 0);
  }
  for (unsigned int i = 0; i < n; ++i)
  {
    double s = 0.;
    for (auto it = damping->begin(i); it != damping->end(i); ++it)
      s += it->value() * D_y[it->column()];
    work[i] += s;
  }
  S_inverse->solve(work);
  q += work;
  work = 0.;
}

void GglFixedBlock::select(const std::vector<bool>& force,
                           const std::vector<bool>& engaged)
{
  force_set = force;
  engaged_set = engaged;
  std::vector<bool> with_lambda(m);
  for (unsigned int k = 0; k < m; ++k)
    with_lambda[k] = force[k] || engaged[k];
  P.select(with_lambda);
  N.select(force);
}

void GglFixedBlock::solve(const std::vector<dealii::Vector<double>*>& xs) const
{
  if (m == 0 || xs.empty())
    return;
  const std::size_t count = xs.size();
  // mu = -N^-1 r_2 and eta = -N^-1 r_0 on F, side by side.
  for (auto* w : {&mu_w, &eta_w, &rhs_w})
    if (w->size() < count)
      w->resize(count, dealii::Vector<double>(m));
  auto &mu = mu_w, &eta = eta_w, &rhs = rhs_w;
  std::vector<dealii::Vector<double>*> batch;
  for (std::size_t j = 0; j < count; ++j)
  {
    for (unsigned int k = 0; k < m; ++k)
    {
      mu[j][k] = force_set[k] ? -(*xs[j])[3 * k + 2] : 0.;
      eta[j][k] = force_set[k] ? -(*xs[j])[3 * k] : 0.;
    }
    batch.push_back(&mu[j]);
    batch.push_back(&eta[j]);
  }
  N.solve(batch);
  // (P + C) lambda = r_1 - P eta - Q mu on F; (law + d N mu)/(1 + d c) - P eta - Q mu on
  // E.
  batch.clear();
  const bool any_engaged =
      std::find(engaged_set.begin(), engaged_set.end(), true) != engaged_set.end();
  for (std::size_t j = 0; j < count; ++j)
  {
    P.vmult(P_eta, eta[j]);
    if (any_engaged) // N mu enters the laws of the engaged ones only
      N.vmult(N_mu, mu[j]);
    for (unsigned int k = 0; k < m; ++k)
      Q_mu[k] = Q.dot(k, mu[j].begin());
    const dealii::Vector<double>& x = *xs[j];
    rhs[j] = 0.;
    for (unsigned int k = 0; k < m; ++k)
      if (force_set[k])
        rhs[j][k] = x[3 * k + 1] - P_eta[k] - Q_mu[k];
      else if (engaged_set[k])
        rhs[j][k] =
            (x[3 * k] + ratio[k] * N_mu[k]) / (1. + ratio[k] * c) - P_eta[k] - Q_mu[k];
    batch.push_back(&rhs[j]);
  }
  P.solve(batch);
  for (std::size_t j = 0; j < count; ++j)
  {
    dealii::Vector<double>& x = *xs[j];
    for (unsigned int k = 0; k < m; ++k)
    {
      x[3 * k] = rhs[j][k];
      x[3 * k + 1] = force_set[k] ? eta[j][k] : 0.;
      x[3 * k + 2] = force_set[k] ? mu[j][k] : 0.;
    }
  }
}
} // namespace pantocat
