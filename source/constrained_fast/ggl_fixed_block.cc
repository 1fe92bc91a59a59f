#include <pantocat/constrained_fast/ggl_fixed_block.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pantocat
{
void GglFixedBlock::initialize(const std::vector<const SparseRow*>& G,
                               const std::vector<const Constraint*>& constraints,
                               const SparseDirectSolver& S, const MassInverse& M,
                               const dealii::SparseMatrix<double>& D,
                               const DampingOverMass& DM, const double c_,
                               const unsigned int n_dofs)
{
  m = G.size();
  n_unknowns = n_dofs;
  c = c_;
  ratio.assign(m, 0.);
  std::vector<double> compliance(m, 0.);
  for (unsigned int k = 0; k < m; ++k)
  {
    ratio[k] = constraints[k]->is_compliant() ? constraints[k]->compliance().damping /
                                                    constraints[k]->compliance().stiffness
                                              : 0.;
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
  Q_by_column.build(Q, m);
  local = LocalBlock();
  N_eta_mu_valid = false;
  selected_once = false;
  P_eta.reinit(m);
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
  // of Y (two sums), four unknowns per multiply-add with a gathered factor.
  // Solves: S once and M twice, each a substitution (a twisted one for long
  // blocks) of about one multiply-add per entry of the factor, with D
  // applied to M^-1 G^T mu for bodies without DampingOverMass's structure.
  // Measured with bench_constraints (FEM + BDF-2, h = 0.2 m, 2026-11-25),
  // both ways take the same time at about 100 constraints (45 us per step);
  // at 200 the solves took 77 instead of 83 us, at 20 26 instead of 22 us.
  damping_rows.assign(m, SparseRow());
  bool structured = true;
  for (unsigned int k = 0; k < m && structured; ++k)
    structured = DM.apply(*G[k], damping_rows[k]);
  if (!structured)
    damping_rows.clear();
  const SparseDirectSolver* M_factor = M.factorised();
  const double solve_cost = S.solve_cost() +
                            2. * (M_factor ? M_factor->solve_cost() : n_dofs) +
                            (structured ? 0. : D.n_nonzero_elements());
  const double columns_cost =
      static_cast<double>(X.n_slice_operations() + 2 * Y.n_slice_operations()) *
      slice_operation_cost;
  set_forces_by_solves(columns_cost > solve_cost);
}

void GglFixedBlock::set_forces_by_solves(const bool solves)
{
  solves_are_cheaper = solves;
  const unsigned int n = solves ? n_unknowns : 0;
  for (auto* v : {&work, &mass_mu, &mass_eta, &D_y})
    v->reinit(n);
}

void GglFixedBlock::add_forces(const std::vector<double>& lambda_plus_eta,
                               const std::vector<double>& eta,
                               const std::vector<double>& mu, dealii::Vector<double>& q,
                               dealii::Vector<double>& u1,
                               dealii::Vector<double>& u2) const
{
  if (!with_eta_mu) // lambda alone: u1, u2 take nothing
  {
    X.add(lambda_plus_eta, q);
    return;
  }
  if (!solves_are_cheaper)
  {
    X.add_with_partners(lambda_plus_eta, mu, q);
    Y.add(mu, u1, eta, u2);
    return;
  }
  // work, mass_mu and mass_eta are zero on entry (and left so).
  const unsigned int n = q.size();
  for (unsigned int k = 0; k < m; ++k)
  {
    rows[k].add_transpose_to(mass_mu, mu[k]);
    rows[k].add_transpose_to(mass_eta, eta[k]);
    rows[k].add_transpose_to(work, lambda_plus_eta[k] + c * mu[k]);
  }
  if (!damping_rows.empty())
    for (unsigned int k = 0; k < m; ++k)
      damping_rows[k].add_transpose_to(work, mu[k]);
  M_inverse->apply(mass_mu);
  M_inverse->apply(mass_eta);
  if (damping_rows.empty())
  {
    damping->vmult(D_y, mass_mu);
    work += D_y;
  }
  S_inverse->solve(work);
  double *w = work.begin(), *y = mass_mu.begin(), *z = mass_eta.begin();
  for (unsigned int i = 0; i < n; ++i)
  {
    q[i] += w[i];
    u1[i] += y[i];
    u2[i] += z[i];
    w[i] = y[i] = z[i] = 0.;
  }
}

GglFixedBlock::ForceSums
GglFixedBlock::sum_forces(const std::vector<double>& lambda_plus_eta,
                          const std::vector<double>& eta,
                          const std::vector<double>& mu) const
{
  Assert(!solves_are_cheaper, dealii::ExcMessage("the forces are added by solves"));
  if (!with_eta_mu)
    return {X.sum(lambda_plus_eta), {nullptr, nullptr, nullptr, nullptr}};
  return {X.sum_with_partners(lambda_plus_eta, mu), Y.sum(mu, eta)};
}

void GglFixedBlock::select(const std::vector<bool>& force,
                           const std::vector<bool>& engaged,
                           const std::vector<bool>& settled)
{
  // Most trials select what the one before selected: all derived from it holds.
  if (selected_once && force == force_set && engaged == engaged_set &&
      settled == settled_set)
    return;
  selected_once = true;
  force_set = force;
  engaged_set = engaged;
  settled_set = settled;
  std::vector<bool>& with_lambda = with_lambda_set;
  with_lambda.resize(m);
  eta_mu_set.resize(m);
  with_eta_mu = false;
  for (unsigned int k = 0; k < m; ++k)
  {
    with_lambda[k] = force[k] || engaged[k];
    eta_mu_set[k] = force[k] && (settled.empty() || !settled[k]);
  }
  // A settled constraint that N couples to one with eta, mu keeps its own: the
  // other's M^-1 G^T mu, M^-1 G^T eta would change its levels 1 and 2.
  for (unsigned int k = 0; k < m; ++k)
    if (force[k] && !settled.empty() && !settled[k])
      N.for_each_coupled(k,
                         [&](const unsigned int l)
                         {
                           if (force[l])
                             eta_mu_set[l] = true;
                         });
  settled_count = 0;
  for (unsigned int k = 0; k < m; ++k)
  {
    with_eta_mu = with_eta_mu || eta_mu_set[k];
    settled_count += force[k] && !eta_mu_set[k];
  }
  any_engaged = std::find(engaged.begin(), engaged.end(), true) != engaged.end();
  P.select(with_lambda);
  // N on the few constraints with eta and mu (those near a contact, and any
  // that settle anew): dense, refactorised only when they change.
  eta_mu_list.clear();
  for (unsigned int k = 0; k < m; ++k)
    if (eta_mu_set[k])
      eta_mu_list.push_back(k);
  eta_mu_dense = eta_mu_list.size() <= max_local_subset;
  if (!eta_mu_dense)
    N.select(eta_mu_set);
  else if (!N_eta_mu_valid || eta_mu_list != factorised_eta_mu_list)
  {
    N.factorize_subset(eta_mu_list, N_eta_mu);
    factorised_eta_mu_list = eta_mu_list;
    N_eta_mu_valid = true;
    // The rows where P eta and Q mu can be non-zero (P is symmetric).
    eta_mu_rows.clear();
    for (const unsigned int l : eta_mu_list)
    {
      P.for_each_coupled(l, [&](const unsigned int k) { eta_mu_rows.push_back(k); });
      for (unsigned int e = Q_by_column.start[l]; e < Q_by_column.start[l + 1]; ++e)
        eta_mu_rows.push_back(Q_by_column.row[e]);
    }
    std::sort(eta_mu_rows.begin(), eta_mu_rows.end());
    eta_mu_rows.erase(std::unique(eta_mu_rows.begin(), eta_mu_rows.end()),
                      eta_mu_rows.end());
  }
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
  // A border column of a constraint's lambda has no entries in these slots,
  // one of its mu none in the eta slots: zero vectors are not solved for.
  std::vector<dealii::Vector<double>*>& batch = batch_w;
  batch.clear();
  std::vector<char>&mu_zero = mu_zero_w, &eta_zero = eta_zero_w;
  mu_zero.resize(count);
  eta_zero.resize(count);
  for (std::size_t j = 0; j < count; ++j)
  {
    bool mu_nonzero = false, eta_nonzero = false;
    for (unsigned int k = 0; k < m; ++k)
    {
      mu[j][k] = eta_mu_set[k] ? -(*xs[j])[3 * k + 2] : 0.;
      eta[j][k] = eta_mu_set[k] ? -(*xs[j])[3 * k] : 0.;
      mu_nonzero = mu_nonzero || mu[j][k] != 0.;
      eta_nonzero = eta_nonzero || eta[j][k] != 0.;
    }
    mu_zero[j] = !mu_nonzero;
    eta_zero[j] = !eta_nonzero;
    if (mu_nonzero)
      batch.push_back(&mu[j]);
    if (eta_nonzero)
      batch.push_back(&eta[j]);
  }
  if (!eta_mu_dense)
    N.solve(batch);
  else // on eta_mu_list, where the right-hand sides have their entries
    for (dealii::Vector<double>* v : batch)
    {
      gathered.resize(eta_mu_list.size());
      for (std::size_t i = 0; i < eta_mu_list.size(); ++i)
        gathered[i] = (*v)[eta_mu_list[i]];
      N_eta_mu.solve(gathered.data());
      for (std::size_t i = 0; i < eta_mu_list.size(); ++i)
        (*v)[eta_mu_list[i]] = gathered[i];
    }
  // Q mu: zero for a zero mu, the others four at a time side by side.
  if (Q_mu_w.size() < count)
    Q_mu_w.resize(count, dealii::Vector<double>(m));
  std::vector<std::size_t>& with_mu = with_mu_w;
  with_mu.clear();
  for (std::size_t j = 0; j < count; ++j)
    if (mu_zero[j])
      Q_mu_w[j] = 0.;
    else
      with_mu.push_back(j);
  if (eta_mu_dense) // mu is zero off eta_mu_list: Q mu only on the rows Q couples to it
    for (const std::size_t j : with_mu)
    {
      Q_mu_w[j] = 0.;
      for (const unsigned int k : eta_mu_rows)
        Q_mu_w[j][k] = Q.dot(k, mu[j].begin());
    }
  else
    for (std::size_t g = 0; g < with_mu.size(); g += 4)
    {
      const double* x[4];
      for (std::size_t l = 0; l < 4; ++l) // unused lanes repeat the first vector
        x[l] = mu[with_mu[g + (g + l < with_mu.size() ? l : 0)]].begin();
      double out[4];
      for (unsigned int k = 0; k < m; ++k)
      {
        Q.dots(k, x, out);
        for (std::size_t l = 0; l < 4 && g + l < with_mu.size(); ++l)
          Q_mu_w[with_mu[g + l]][k] = out[l];
      }
    }
  // (P + C) lambda = r_1 - P eta - Q mu on F; (law + d N mu)/(1 + d c) - P eta - Q mu on
  // E.
  batch.clear();
  for (std::size_t j = 0; j < count; ++j)
  {
    if (eta_zero[j])
      P_eta = 0.;
    else if (eta_mu_dense) // eta is zero off eta_mu_list
    {
      P_eta = 0.;
      for (const unsigned int k : eta_mu_rows)
        P_eta[k] = P.row_product(k, eta[j].begin());
    }
    else
      P.vmult(P_eta, eta[j]);
    if (any_engaged) // N mu enters the laws of the engaged ones only
    {
      if (mu_zero[j])
        N_mu = 0.;
      else
        N.vmult(N_mu, mu[j]);
    }
    const dealii::Vector<double>&x = *xs[j], &Q_mu = Q_mu_w[j];
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
      x[3 * k + 1] = eta_mu_set[k] ? eta[j][k] : 0.;
      x[3 * k + 2] = eta_mu_set[k] ? mu[j][k] : 0.;
    }
  }
}

bool GglFixedBlock::local_subset(const std::vector<unsigned int>& sources)
{
  constexpr double unit_roundoff = 0.5 * std::numeric_limits<double>::epsilon();
  LocalBlock& L = local;
  std::vector<bool>& reached = L.reached;
  reached.resize(m, false);
  // eta and mu: the reach of N among the constraints that have them.
  N.reach_from(sources, eta_mu_set, unit_roundoff, reached);
  L.eta_mu.clear();
  for (unsigned int k = 0; k < m; ++k)
    if (reached[k])
      L.eta_mu.push_back(k);
  // lambda: the reach of P + C from the sources, those with eta and mu, and
  // the rows their Q mu (and, on engaged ones, N mu) enters.
  std::vector<unsigned int>& seeds = L.seeds;
  seeds.clear();
  for (const unsigned int k : sources)
    if (with_lambda_set[k])
      seeds.push_back(k);
  for (const unsigned int l : L.eta_mu)
  {
    seeds.push_back(l);
    for (unsigned int e = Q_by_column.start[l]; e < Q_by_column.start[l + 1]; ++e)
      if (with_lambda_set[Q_by_column.row[e]])
        seeds.push_back(Q_by_column.row[e]);
    if (any_engaged)
      N.for_each_coupled(l,
                         [&](const unsigned int k)
                         {
                           if (engaged_set[k])
                             seeds.push_back(k);
                         });
  }
  P.reach_from(seeds, with_lambda_set, unit_roundoff, reached);
  L.subset.clear();
  for (unsigned int k = 0; k < m; ++k)
    if (reached[k])
    {
      L.subset.push_back(k);
      reached[k] = false;
    }
  return L.subset.size() <= max_local_subset;
}

void GglFixedBlock::solve_local(const std::vector<dealii::Vector<double>*>& xs)
{
  LocalBlock& L = local;
  if (!L.factorised || L.subset != L.factorised_subset || L.eta_mu != L.factorised_eta_mu)
  {
    P.factorize_subset(L.subset, L.P_factor);
    N.factorize_subset(L.eta_mu, L.N_factor);
    L.factorised_subset = L.subset;
    L.factorised_eta_mu = L.eta_mu;
    L.factorised = true;
  }
  const unsigned int r = L.subset.size(), e = L.eta_mu.size();
  L.eta_full.resize(m, 0.);
  L.mu_full.resize(m, 0.);
  L.rhs.resize(r);
  L.eta.resize(e);
  L.mu.resize(e);
  for (dealii::Vector<double>* xp : xs)
  {
    dealii::Vector<double>& x = *xp;
    // mu = -N^-1 r_1, eta = -N^-1 r_2 on those with eta and mu (solve()).
    for (unsigned int i = 0; i < e; ++i)
    {
      const unsigned int k = L.eta_mu[i];
      L.mu[i] = -x[3 * k + 2];
      L.eta[i] = -x[3 * k];
    }
    if (e > 0)
    {
      L.N_factor.solve(L.mu.data());
      L.N_factor.solve(L.eta.data());
    }
    for (unsigned int i = 0; i < e; ++i)
    {
      L.mu_full[L.eta_mu[i]] = L.mu[i];
      L.eta_full[L.eta_mu[i]] = L.eta[i];
    }
    // (P + C) lambda = r_0 - P eta - Q mu, the engaged rows' laws as in solve().
    for (unsigned int i = 0; i < r; ++i)
    {
      const unsigned int k = L.subset[i];
      const double P_eta = e > 0 ? P.row_product(k, L.eta_full.data()) : 0.,
                   Q_mu = e > 0 ? Q.dot(k, L.mu_full.data()) : 0.;
      if (force_set[k])
        L.rhs[i] = x[3 * k + 1] - P_eta - Q_mu;
      else
      {
        const double N_mu = e > 0 ? N.row_product(k, L.mu_full.data()) : 0.;
        L.rhs[i] = (x[3 * k] + ratio[k] * N_mu) / (1. + ratio[k] * c) - P_eta - Q_mu;
      }
    }
    if (r > 0)
      L.P_factor.solve(L.rhs.data());
    for (unsigned int i = 0; i < r; ++i)
    {
      const unsigned int k = L.subset[i];
      x[3 * k] = L.rhs[i];
      x[3 * k + 1] = x[3 * k + 2] = 0.;
    }
    for (unsigned int i = 0; i < e; ++i)
    {
      const unsigned int k = L.eta_mu[i];
      x[3 * k + 1] = L.eta[i];
      x[3 * k + 2] = L.mu[i];
      L.eta_full[k] = L.mu_full[k] = 0.;
    }
  }
}
} // namespace pantocat
