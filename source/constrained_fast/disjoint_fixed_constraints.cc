#include <pantocat/constrained/unconstrained_prediction.h>
#include <pantocat/constrained_fast/disjoint_fixed_constraints.h>

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
    const bool pair = row.size() == 2;
    pairs.j0.push_back(pair ? row.index[0] : 0);
    pairs.j1.push_back(pair ? row.index[1] : 0);
    pairs.g0.push_back(pair ? row.value[0] : 0.);
    pairs.g1.push_back(pair ? row.value[1] : 0.);
    pairs.w0.push_back(pair ? w_col[0] : 0.);
    pairs.w1.push_back(pair ? w_col[1] : 0.);
    pairs.m0.push_back(pair ? m_col[0] : 0.);
    pairs.m1.push_back(pair ? m_col[1] : 0.);
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

namespace
{
/// The coefficients of the constraints [first, first + count) with two unknowns.
struct PairChunk
{
  const unsigned int *j0, *j1;
  const double *g0, *g1, *w0, *w1, *m0, *m1, *inverse_w, *inverse_m, *offset;
};

/// The state a chunk reads and writes (DisjointFixedConstraints::Prediction and a).
struct PairState
{
  double* a;
  const double *q, *v, *v_previous;
  double *q_new, *v_new;
  double dt;
};

/**
 * accelerate() and project_one() of the @p count <= B constraints of @p c
 * (indexed from 0), each with two unknowns, phase by phase: the state's
 * entries are gathered into arrays, the arithmetic runs over all of them (in
 * four-double vectors in the AVX2 clone: the coefficients of consecutive
 * constraints are consecutive, the unknowns of two constraints never the same),
 * then the results are scattered. Per constraint the operations and their
 * order are those of accelerate() and project_one(), without fused
 * multiply-adds: the same bits. @p lambda_out, @p gap_out: lambda_k (where
 * selected for (39)) and the gap at t_{n+1}.
 */
template <unsigned int B>
__attribute__((target_clones("avx2", "default"))) void
accelerate_and_project_pairs(const PairChunk& c, const unsigned int count,
                             const PairState& p, double* __restrict lambda_out,
                             double* __restrict gap_out)
{
  double a0[B], a1[B], vp0[B], vp1[B], qn0[B], qn1[B], vn0[B], vn1[B];
  double q0[B], q1[B], v0[B], v1[B];
  for (unsigned int b = 0; b < count; ++b)
  {
    const unsigned int i0 = c.j0[b], i1 = c.j1[b];
    a0[b] = p.a[i0];
    a1[b] = p.a[i1];
    vp0[b] = p.v_previous[i0];
    vp1[b] = p.v_previous[i1];
    qn0[b] = p.q[i0];
    qn1[b] = p.q[i1];
    vn0[b] = p.v[i0];
    vn1[b] = p.v[i1];
  }
  const double two_dt = 2. * p.dt, half_dt = 0.5 * p.dt, h = p.dt;
  // The coefficients as local restrict pointers: loaded once, not per row.
  const double* __restrict g0 = c.g0;
  const double* __restrict g1 = c.g1;
  const double* __restrict w0 = c.w0;
  const double* __restrict w1 = c.w1;
  const double* __restrict m0 = c.m0;
  const double* __restrict m1 = c.m1;
  const double* __restrict inverse_w = c.inverse_w;
  const double* __restrict inverse_m = c.inverse_m;
  const double* __restrict offset = c.offset;
  for (unsigned int b = 0; b < count; ++b)
  {
    // (39). Both branches are computed, then selected: no operation under a
    // condition, so that gcc vectorises the loop (this file is built with
    // -fno-trapping-math, CMakeLists.txt).
    const double inverse = inverse_w[b];
    const bool selected = inverse != 0.;
    const double s = 0. + g0[b] * a0[b] + g1[b] * a1[b];
    const double product = -s * inverse;
    const double l = selected ? product : 0.;
    const double moved0 = a0[b] + l * w0[b], moved1 = a1[b] + l * w1[b];
    a0[b] = selected ? moved0 : a0[b];
    a1[b] = selected ? moved1 : a1[b];
    lambda_out[b] = l;
    // The prediction from the final a.
    double x0 = vp0[b] + two_dt * a0[b], x1 = vp1[b] + two_dt * a1[b];
    double y0 = qn0[b] + half_dt * (vn0[b] + x0), y1 = qn1[b] + half_dt * (vn1[b] + x1);
    // (40)
    const double inverse_mb = inverse_m[b];
    const double sq = 0. + g0[b] * y0 + g1[b] * y1;
    const double sv = 0. + g0[b] * x0 + g1[b] * x1;
    const double r_g = -(sq + offset[b]), r_v = -sv;
    const double eta = r_v * inverse_mb / (2. * h);
    const double mu = r_g * inverse_mb / h - h * eta;
    const double fq = h * h * eta + h * mu, fv = 2. * h * eta;
    const bool projected = inverse_mb != 0.;
    const double yp0 = y0 + fq * m0[b], xp0 = x0 + fv * m0[b];
    const double yp1 = y1 + fq * m1[b], xp1 = x1 + fv * m1[b];
    y0 = projected ? yp0 : y0;
    x0 = projected ? xp0 : x0;
    y1 = projected ? yp1 : y1;
    x1 = projected ? xp1 : x1;
    q0[b] = y0;
    q1[b] = y1;
    v0[b] = x0;
    v1[b] = x1;
    gap_out[b] = 0. + g0[b] * y0 + g1[b] * y1 + offset[b];
  }
  for (unsigned int b = 0; b < count; ++b)
  {
    const unsigned int i0 = c.j0[b], i1 = c.j1[b];
    p.a[i0] = a0[b]; // unchanged where not selected
    p.a[i1] = a1[b];
    p.q_new[i0] = q0[b];
    p.q_new[i1] = q1[b];
    p.v_new[i0] = v0[b];
    p.v_new[i1] = v1[b];
  }
}
} // namespace

void DisjointFixedConstraints::accelerate_and_project(
    const unsigned int first, const unsigned int count, double* __restrict a,
    std::vector<double>& lambda, const Prediction& p, std::vector<double>& gaps) const
{
  const PairChunk c{
      pairs.j0.data() + first,  pairs.j1.data() + first, pairs.g0.data() + first,
      pairs.g1.data() + first,  pairs.w0.data() + first, pairs.w1.data() + first,
      pairs.m0.data() + first,  pairs.m1.data() + first, inverse_w.data() + first,
      inverse_m.data() + first, offset.data() + first};
  double l[batch], g[batch];
  accelerate_and_project_pairs<batch>(
      c, count, PairState{a, p.q, p.v, p.v_previous, p.q_new, p.v_new, p.dt}, l, g);
  for (unsigned int b = 0; b < count; ++b)
  {
    const unsigned int k = first + b;
    if (inverse_w[k] != 0.)
      lambda[id[k]] = l[b];
    gaps[id[k]] = g[b];
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
  for (unsigned int i = 0; i < count; ++i)
  {
    const unsigned int k = which ? which[i] : i;
    if (predict && project_now)
    {
      // Consecutive droppers (two unknowns each) that no moving constraint
      // borders, in batches.
      unsigned int n_batch = 0;
      for (unsigned int next = i; n_batch < batch && next < count; ++next)
      {
        const unsigned int l = which ? which[next] : next;
        if (l != k + n_batch || !(*project_now)[l] || start[l + 1] - start[l] != 2)
          break;
        ++n_batch;
      }
      if (n_batch > 0)
      {
        accelerate_and_project(k, n_batch, a, lambda, *predict, *gaps);
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
