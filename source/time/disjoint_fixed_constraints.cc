#include <pantocat/time/disjoint_fixed_constraints.h>
#include <pantocat/time/unconstrained_prediction.h>

#include <algorithm>

namespace pantocat
{
namespace
{
/// W^-1 row^T at the row's own unknowns, or false if it reaches beyond them.
bool column_on_row(const SparseRow& row, const MassInverse& A,
                   dealii::Vector<double>& column, std::vector<double>& out)
{
  A.apply_to_row(row, column);
  out.clear();
  for (const unsigned int j : row.index)
    out.push_back(column[j]);
  bool local = true;
  for (const unsigned int j : A.coupled())
    local = local && (column[j] == 0. || std::find(row.index.begin(), row.index.end(),
                                                   j) != row.index.end());
  A.reset_column(row, column);
  return local;
}
} // namespace

bool DisjointFixedConstraints::initialize(const CompressedRows& rows,
                                          const std::vector<double>& offsets,
                                          const std::vector<unsigned int>& ids,
                                          const MassInverse& W, const MassInverse& M,
                                          const unsigned int n_dofs)
{
  *this = DisjointFixedConstraints();
  if (rows.size() == 0 || !W.row_scaling() || !M.row_scaling())
    return false;
  // No unknown in two rows, none in a coupled block.
  std::vector<bool> taken(n_dofs, false);
  for (const std::vector<unsigned int>* coupled : {&W.coupled(), &M.coupled()})
    for (const unsigned int j : *coupled)
      taken[j] = true;
  for (const unsigned int j : rows.index)
  {
    if (taken[j])
      return false;
    taken[j] = true;
  }
  dealii::Vector<double> column(n_dofs);
  std::vector<double> w_col, m_col;
  SparseRow row;
  for (unsigned int k = 0; k < rows.size(); ++k)
  {
    row.clear();
    for (unsigned int e = rows.start[k]; e < rows.start[k + 1]; ++e)
      row.add(rows.index[e], rows.value[e]);
    if (!column_on_row(row, W, column, w_col) || !column_on_row(row, M, column, m_col))
    {
      *this = DisjointFixedConstraints();
      return false;
    }
    double sw = 0., sm = 0.; // in SparseRow::dot()'s order, as FixedConstraintSchur
    for (std::size_t e = 0; e < row.size(); ++e)
    {
      entries.push_back({row.index[e], row.value[e], w_col[e], m_col[e]});
      sw += row.value[e] * w_col[e];
      sm += row.value[e] * m_col[e];
    }
    start.push_back(entries.size());
    schur_w.push_back(sw);
    schur_m.push_back(sm);
  }
  offset = offsets;
  id = ids;
  inverse_w.assign(rows.size(), 0.);
  inverse_m.assign(rows.size(), 0.);
  in_use = true;
  return true;
}

namespace
{
void select(const std::vector<bool>& keep, const unsigned long version,
            const std::vector<double>& schur, unsigned long& selected,
            std::vector<double>& inverse)
{
  if (version == selected && version != 0)
    return;
  selected = version;
  for (std::size_t k = 0; k < schur.size(); ++k)
    inverse[k] = keep[k] ? 1. / (schur[k] + 0.) : 0.; // as FixedConstraintSchur::select
}
} // namespace

void DisjointFixedConstraints::select_acceleration(const std::vector<bool>& keep,
                                                   const unsigned long version)
{
  select(keep, version, schur_w, selected_w, inverse_w);
}

void DisjointFixedConstraints::select_position(const std::vector<bool>& keep,
                                               const unsigned long version)
{
  select(keep, version, schur_m, selected_m, inverse_m);
}

void DisjointFixedConstraints::accelerate_and_project(
    const unsigned int* ks, const unsigned int count, double* __restrict a,
    std::vector<double>& lambda, const Prediction& p, std::vector<double>& gaps) const
{
  // Constraints ks[0 .. count) with two unknowns each, their values
  // in registers and each phase over all of them: each value is loaded and
  // stored once, and the constraints' chains of dependent operations (two
  // divisions among them) overlap instead of following one another. The
  // operations and their order per constraint are those of accelerate() and
  // project_one(): the same bits.
  constexpr unsigned int B = batch;
  const Entry* x[B];
  for (unsigned int b = 0; b < count; ++b)
    x[b] = entries.data() + start[ks[b]];
  unsigned int j0[B], j1[B];
  double a0[B], a1[B], q0[B], q1[B], v0[B], v1[B], l[B];
  for (unsigned int b = 0; b < count; ++b)
  {
    j0[b] = x[b][0].unknown;
    j1[b] = x[b][1].unknown;
    a0[b] = a[j0[b]];
    a1[b] = a[j1[b]];
  }
  // (39)
  for (unsigned int b = 0; b < count; ++b)
  {
    const double inverse = inverse_w[ks[b]];
    const Entry& e0 = x[b][0];
    const Entry& e1 = x[b][1];
    const double s = 0. + e0.g * a0[b] + e1.g * a1[b];
    l[b] = inverse != 0. ? -s * inverse : 0.;
    a0[b] = inverse != 0. ? a0[b] + l[b] * e0.w_col : a0[b];
    a1[b] = inverse != 0. ? a1[b] + l[b] * e1.w_col : a1[b];
  }
  const double two_dt = 2. * p.dt, half_dt = 0.5 * p.dt, h = p.dt;
  for (unsigned int b = 0; b < count; ++b)
  {
    v0[b] = p.v_previous[j0[b]] + two_dt * a0[b];
    v1[b] = p.v_previous[j1[b]] + two_dt * a1[b];
    q0[b] = p.q[j0[b]] + half_dt * (p.v[j0[b]] + v0[b]);
    q1[b] = p.q[j1[b]] + half_dt * (p.v[j1[b]] + v1[b]);
  }
  // (40)
  for (unsigned int b = 0; b < count; ++b)
  {
    const double inverse = inverse_m[ks[b]];
    const Entry& e0 = x[b][0];
    const Entry& e1 = x[b][1];
    const double sq = 0. + e0.g * q0[b] + e1.g * q1[b];
    const double sv = 0. + e0.g * v0[b] + e1.g * v1[b];
    const double r_g = -(sq + offset[ks[b]]), r_v = -sv;
    const double eta = r_v * inverse / (2. * h);
    const double mu = r_g * inverse / h - h * eta;
    const double fq = h * h * eta + h * mu, fv = 2. * h * eta;
    if (inverse != 0.)
    {
      q0[b] += fq * e0.m_col;
      v0[b] += fv * e0.m_col;
      q1[b] += fq * e1.m_col;
      v1[b] += fv * e1.m_col;
    }
  }
  for (unsigned int b = 0; b < count; ++b)
  {
    const unsigned int k = ks[b];
    if (inverse_w[k] != 0.)
    {
      lambda[id[k]] = l[b];
      a[j0[b]] = a0[b];
      a[j1[b]] = a1[b];
    }
    p.q_new[j0[b]] = q0[b];
    p.q_new[j1[b]] = q1[b];
    p.v_new[j0[b]] = v0[b];
    p.v_new[j1[b]] = v1[b];
    gaps[id[k]] = 0. + x[b][0].g * q0[b] + x[b][1].g * q1[b] + offset[k];
  }
}

void DisjointFixedConstraints::accelerate(double* a, std::vector<double>& lambda,
                                          const Prediction* predict,
                                          const std::vector<bool>* project_now,
                                          std::vector<double>* gaps) const
{
  accelerate(nullptr, id.size(), a, lambda, predict, project_now, gaps);
}

void DisjointFixedConstraints::accelerate(const unsigned int* which,
                                          const unsigned int count, double* __restrict a,
                                          std::vector<double>& lambda,
                                          const Prediction* predict,
                                          const std::vector<bool>* project_now,
                                          std::vector<double>* gaps) const
{
  const Entry* __restrict x = entries.data();
  unsigned int ks[batch];
  for (unsigned int i = 0; i < count; ++i)
  {
    const unsigned int k = which ? which[i] : i;
    if (predict && project_now)
    {
      // Droppers (two unknowns each) that no moving constraint borders, in batches.
      unsigned int n_batch = 0;
      for (unsigned int next = i; n_batch < batch && next < count; ++next)
      {
        const unsigned int l = which ? which[next] : next;
        if (!(*project_now)[l] || start[l + 1] - start[l] != 2)
          break;
        ks[n_batch++] = l;
      }
      if (n_batch > 0)
      {
        accelerate_and_project(ks, n_batch, a, lambda, *predict, *gaps);
        i += n_batch - 1;
        continue;
      }
    }
    const unsigned int first = start[k], last = start[k + 1];
    if (const double inverse = inverse_w[k]; inverse != 0.)
    {
      double s = 0.;
      for (unsigned int e = first; e < last; ++e)
        s += x[e].g * a[x[e].unknown];
      const double l = -s * inverse;
      lambda[id[k]] = l;
      for (unsigned int e = first; e < last; ++e)
        a[x[e].unknown] += l * x[e].w_col;
    }
    if (!predict)
      continue;
    const double dt = predict->dt;
    for (unsigned int e = first; e < last; ++e)
    {
      const unsigned int j = x[e].unknown;
      predict_unconstrained(j, a[j], 2. * dt, 0.5 * dt, predict->q, predict->v,
                            predict->v_previous, predict->q_new, predict->v_new);
    }
    if (project_now && (*project_now)[k])
      project_one(k, predict->q_new, predict->v_new, dt, *gaps);
  }
}

void DisjointFixedConstraints::project_one(const unsigned int k, double* __restrict q,
                                           double* __restrict v, const double h,
                                           std::vector<double>& gaps) const
{
  const Entry* __restrict x = entries.data();
  const unsigned int first = start[k], last = start[k + 1];
  if (const double inverse = inverse_m[k]; inverse != 0.)
  {
    double sq = 0., sv = 0.;
    for (unsigned int e = first; e < last; ++e)
    {
      sq += x[e].g * q[x[e].unknown];
      sv += x[e].g * v[x[e].unknown];
    }
    // The fixed block [h^2 S, h S; 2h S, 0] of (40) for one constraint.
    const double r_g = -(sq + offset[k]), r_v = -sv;
    const double eta = r_v * inverse / (2. * h);
    const double mu = r_g * inverse / h - h * eta;
    const double fq = h * h * eta + h * mu, fv = 2. * h * eta;
    for (unsigned int e = first; e < last; ++e)
    {
      q[x[e].unknown] += fq * x[e].m_col;
      v[x[e].unknown] += fv * x[e].m_col;
    }
  }
  double gap = 0.;
  for (unsigned int e = first; e < last; ++e)
    gap += x[e].g * q[x[e].unknown];
  gaps[id[k]] = gap + offset[k];
}

void DisjointFixedConstraints::project(double* q, double* v, const double h,
                                       std::vector<double>& gaps) const
{
  for (unsigned int k = 0; k < id.size(); ++k)
    project_one(k, q, v, h, gaps);
}

void DisjointFixedConstraints::project(double* q, double* v, const double h,
                                       std::vector<double>& gaps,
                                       const std::vector<unsigned int>& which) const
{
  for (const unsigned int k : which)
    project_one(k, q, v, h, gaps);
}
} // namespace pantocat
