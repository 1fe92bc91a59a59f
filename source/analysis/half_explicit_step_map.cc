#include <pantocat/analysis/half_explicit_step_map.h>
#include <pantocat/lac/diagonal_force_sweep.h>
#include <pantocat/lac/sparse_direct_solver.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

namespace pantocat
{
class HalfExplicitStepMap::BlockInverse
{
public:
  /// The inverse of M + @p damping_factor D, one factorisation per body block.
  BlockInverse(const SemiDiscreteSystem& system, const double damping_factor)
  {
    for (const DofBlock& b : system.blocks)
    {
      Part p;
      p.first = b.first;
      p.size = b.size;
      p.diagonal.reinit(b.size);
      bool diagonal = true;
      dealii::DynamicSparsityPattern dsp(b.size, b.size);
      for (unsigned int i = 0; i < b.size; ++i)
        for (auto it = system.sparsity->begin(b.first + i);
             it != system.sparsity->end(b.first + i); ++it)
        {
          const unsigned int j = it->column();
          const double value = system.mass(b.first + i, j) +
                               damping_factor * system.damping(b.first + i, j);
          if (value == 0.)
            continue;
          if (j < b.first || j >= b.first + b.size)
            throw std::logic_error("HalfExplicitStepMap: M or D couples two blocks");
          dsp.add(i, j - b.first);
          if (j == b.first + i)
            p.diagonal(i) = value;
          else
            diagonal = false;
        }
      if (diagonal)
        for (unsigned int i = 0; i < b.size; ++i)
          p.diagonal(i) = 1. / p.diagonal(i);
      else
      {
        p.pattern = std::make_unique<dealii::SparsityPattern>();
        p.pattern->copy_from(dsp);
        p.matrix.reinit(*p.pattern);
        for (unsigned int i = 0; i < b.size; ++i)
          for (auto it = system.sparsity->begin(b.first + i);
               it != system.sparsity->end(b.first + i); ++it)
          {
            const unsigned int j = it->column();
            const double value = system.mass(b.first + i, j) +
                                 damping_factor * system.damping(b.first + i, j);
            if (value != 0.)
              p.matrix.set(i, j - b.first, value);
          }
        p.lu = std::make_unique<SparseDirectSolver>();
        p.lu->factorize(p.matrix, "matrix M + dt/2 D");
        p.work.reinit(b.size);
      }
      parts.push_back(std::move(p));
    }
    for (unsigned int k = 0; k < parts.size(); ++k)
      for (unsigned int i = 0; i < parts[k].size; ++i)
        part_of.push_back(k);
    // All blocks at once: the banded solver sweeps two independent blocks side
    // by side, whose latency-bound recurrences then overlap.
    dealii::SparseMatrix<double> whole_matrix(*system.sparsity);
    whole_matrix.copy_from(system.mass);
    whole_matrix.add(damping_factor, system.damping);
    whole.factorize(whole_matrix, "matrix M + dt/2 D");
  }

  /// x <- A^-1 x in the blocks flagged in @p touched (all if empty).
  void solve(dealii::Vector<double>& x, const std::vector<bool>& touched = {}) const
  {
    if (touched.empty() && whole.is_banded())
    {
      whole.solve_interleaved(x.begin(), 1);
      return;
    }
    for (unsigned int k = 0; k < parts.size(); ++k)
      if (touched.empty() || touched[k])
      {
        const Part& p = parts[k];
        if (!p.lu)
        {
          for (unsigned int i = 0; i < p.size; ++i)
            x(p.first + i) *= p.diagonal(i);
          continue;
        }
        if (p.lu->is_banded())
          p.lu->solve_interleaved(x.begin() + p.first, 1); // in place
        else
        {
          for (unsigned int i = 0; i < p.size; ++i)
            p.work(i) = x(p.first + i);
          p.lu->solve(p.work);
          for (unsigned int i = 0; i < p.size; ++i)
            x(p.first + i) = p.work(i);
        }
      }
  }

  unsigned int n_parts() const { return parts.size(); }
  unsigned int part(const unsigned int dof) const { return part_of[dof]; }

private:
  struct Part
  {
    unsigned int first = 0, size = 0;
    dealii::Vector<double> diagonal; ///< inverse diagonal, if the block is diagonal
    std::unique_ptr<dealii::SparsityPattern> pattern;
    dealii::SparseMatrix<double> matrix;
    std::unique_ptr<SparseDirectSolver> lu; ///< banded Cholesky (or UMFPACK)
    mutable dealii::Vector<double> work;
  };
  std::vector<Part> parts;
  std::vector<unsigned int> part_of;
  SparseDirectSolver whole; ///< of all blocks, used if banded
};

/**
 * A column of a banded inverse, M^-1 G^T and the like, kept on its support
 * only: entries [first, first + values.size()) of a vector that is exactly
 * zero elsewhere. The columns of a diagonal mass have a few entries; those of
 * a banded inverse decay by a constant factor per row until they underflow,
 * some thousand rows for a consistent mass. Their entries below 1e-17 of the
 * largest at either end are dropped (they no longer change a sum in double
 * precision): the passes over a column cost O(support), and m columns of a
 * long section O(m support) memory, not O(m n).
 */
struct HalfExplicitStepMap::CompactColumn
{
  unsigned int first = 0;
  std::vector<double> values;

  unsigned int last() const { return first + values.size(); }

  /// Keeps @p x (which it leaves unchanged) less the small entries at its ends.
  void assign_truncated(const dealii::Vector<double>& x)
  {
    const double small = 1e-17 * x.linfty_norm();
    unsigned int lo = 0, hi = x.size();
    while (lo < hi && std::abs(x[lo]) < small)
      ++lo;
    while (hi > lo && std::abs(x[hi - 1]) < small)
      --hi;
    // Zeros inside the kept range stay (exactly as in the full vector).
    while (lo < hi && x[lo] == 0.)
      ++lo;
    while (hi > lo && x[hi - 1] == 0.)
      --hi;
    first = lo;
    values.assign(x.begin() + lo, x.begin() + hi);
  }

  /// row . column, the row's entries in order (those outside the support add 0).
  double dot(const SparseRow& row) const
  {
    double sum = 0.;
    for (std::size_t e = 0; e < row.size(); ++e)
      if (row.index[e] >= first && row.index[e] < last())
        sum += row.value[e] * values[row.index[e] - first];
    return sum;
  }

  /// y += a column on the support (y unchanged elsewhere, where it is zero).
  void add_to(dealii::Vector<double>& y, const double a) const
  {
    for (unsigned int i = 0; i < values.size(); ++i)
      y[first + i] += a * values[i];
  }
};

/**
 * K and D/2 stored by diagonals and swept by DiagonalForceSweep, as the
 * integrator does: -K q - D (v_prev + v)/2 with the coefficients of a uniform
 * wire's rows read from registers, where two deal.II products and three
 * vector updates would make five passes over the memory.
 */
struct HalfExplicitStepMap::Forces
{
  ForceDiagonals diagonals;
  std::vector<double> zero;
  DiagonalForceSweep sweep;

  explicit Forces(const SemiDiscreteSystem& system)
      : diagonals(system.stiffness, system.damping), zero(system.n_dofs(), 0.)
  {
    const ForceDiagonals& d = diagonals;
    sweep.initialize(system.n_dofs(), d.bandwidth, d.stiffness_offsets, d.stiffness,
                     d.damping_offsets, d.half_damping);
  }

  /// r = -K q - D (v_prev + v) / 2
  void apply(const HalfExplicitStepMap::State& x, dealii::Vector<double>& r)
  {
    sweep.apply(zero.data(), x.q.begin(), x.v_prev.begin(), x.v.begin(), r.begin());
  }
};

/// The rows of the constraints at t_n, t_{n+1/2}, t_{n+1} and their columns.
struct HalfExplicitStepMap::Rows
{
  std::vector<ConstraintState> at_n, at_half, at_next;
  /// Y = (M + dt/2 D)^-1 G(t_n)^T, P = M^-1 G(t_n)^T, Q = M^-1 G_t(t_{n+1/2})^T,
  /// R = M^-1 G(t_{n+1/2})^T, for the rigid constraints, on their supports.
  std::vector<CompactColumn> Y, P, Q, R;
  /// The full vector each column is solved in before it is kept.
  dealii::Vector<double> scratch;
  /// The inverses of the multipliers' matrices at the acceleration and at the
  /// position level, kept from step to step while no rigid row moves.
  dealii::FullMatrix<double> acceleration_inverse, position_inverse;
  bool rigid_rows_move = false;
};

HalfExplicitStepMap::HalfExplicitStepMap(const SemiDiscreteSystem& system,
                                         const std::vector<bool>& active, const double dt)
    : system(system), dt(dt), mass_inverse(std::make_unique<BlockInverse>(system, 0.)),
      smoothed_inverse(std::make_unique<BlockInverse>(system, 0.5 * dt)),
      forces(std::make_unique<Forces>(system)), rows(std::make_unique<Rows>())
{
  const unsigned int n = system.n_dofs(), m = system.n_constraints();
  for (unsigned int i = 0; i < m; ++i)
    if (i < active.size() && active[i])
      (system.constraints[i]->is_compliant() ? springs : rigid).push_back(i);
  for (auto* x : {&a, &q_new, &v_new})
    x->reinit(n);
  rows->at_n.resize(m);
  rows->at_half.resize(m);
  rows->at_next.resize(m);
  for (auto* c : {&rows->Y, &rows->P, &rows->Q, &rows->R})
    c->assign(rigid.size(), CompactColumn());
  rows->scratch.reinit(n);
  // The constant rows and their columns, once.
  for (unsigned int i = 0; i < m; ++i)
    if (!system.constraints[i]->depends_on_time())
    {
      system.constraints[i]->evaluate(0., rows->at_n[i]);
      rows->at_half[i] = rows->at_n[i];
      rows->at_next[i] = rows->at_n[i];
    }
  for (const unsigned int i : rigid)
    rows->rigid_rows_move =
        rows->rigid_rows_move || system.constraints[i]->depends_on_time();
  for (unsigned int k = 0; k < rigid.size(); ++k)
    if (!system.constraints[rigid[k]]->depends_on_time())
    {
      const ConstraintState& s = rows->at_n[rigid[k]];
      column(*smoothed_inverse, s.G, rows->Y[k]);
      column(*mass_inverse, s.G, rows->P[k]);
      column(*mass_inverse, s.G_t, rows->Q[k]);
      rows->R[k] = rows->P[k];
    }
}

HalfExplicitStepMap::~HalfExplicitStepMap() = default;

void HalfExplicitStepMap::column(const BlockInverse& inverse, const SparseRow& row,
                                 CompactColumn& out) const
{
  dealii::Vector<double>& x = rows->scratch;
  x = 0.;
  std::vector<bool> touched(inverse.n_parts(), false);
  for (std::size_t e = 0; e < row.size(); ++e)
  {
    x(row.index[e]) += row.value[e];
    touched[inverse.part(row.index[e])] = true;
  }
  inverse.solve(x, touched);
  out.assign_truncated(x);
}

void HalfExplicitStepMap::evaluate_rows(const double t_n, const double t_half,
                                        const double t_next)
{
  for (unsigned int i = 0; i < system.n_constraints(); ++i)
    if (system.constraints[i]->depends_on_time())
    {
      system.constraints[i]->evaluate(t_n, rows->at_n[i], 2);
      system.constraints[i]->evaluate(t_half, rows->at_half[i], 1);
      system.constraints[i]->evaluate(t_next, rows->at_next[i], 1);
    }
  for (unsigned int k = 0; k < rigid.size(); ++k)
    if (system.constraints[rigid[k]]->depends_on_time())
    {
      const unsigned int i = rigid[k];
      column(*smoothed_inverse, rows->at_n[i].G, rows->Y[k]);
      column(*mass_inverse, rows->at_n[i].G, rows->P[k]);
      column(*mass_inverse, rows->at_half[i].G_t, rows->Q[k]);
      column(*mass_inverse, rows->at_half[i].G, rows->R[k]);
    }
}

void HalfExplicitStepMap::apply(const double t_n, const double t_half,
                                const double t_next, State& x)
{
  evaluate_rows(t_n, t_half, t_next);
  const auto& sn = rows->at_n;
  const auto& s1 = rows->at_next;
  const double h = dt;

  // (39) with (41): (M + dt/2 D) a = -K q - D (v_prev + v)/2 + the springs.
  forces->apply(x, a);
  for (const unsigned int i : springs)
  {
    const ConstraintState& s = sn[i];
    const Compliance& c = system.constraints[i]->compliance();
    const double lambda =
        -c.stiffness * s.G.dot(x.q) -
        c.damping * (s.G_t.dot(x.q) + 0.5 * (s.G.dot(x.v_prev) + s.G.dot(x.v)));
    s.G.add_transpose_to(a, lambda);
  }
  smoothed_inverse->solve(a);

  // The rigid multipliers: g^(II) = G a + 2 G_t v + G_tt q = 0 at t_n.
  const unsigned int m = rigid.size();
  if (m > 0)
  {
    dealii::FullMatrix<double>& S = rows->acceleration_inverse;
    const bool form = rows->rigid_rows_move || S.m() != m;
    if (form)
      S.reinit(m, m);
    dealii::Vector<double> rhs(m), lambda(m);
    for (unsigned int k = 0; k < m; ++k)
    {
      const ConstraintState& s = sn[rigid[k]];
      if (form)
        for (unsigned int l = 0; l < m; ++l)
          S(k, l) = rows->Y[l].dot(s.G);
      rhs(k) = -(s.G.dot(a) + 2. * s.G_t.dot(x.v) + s.G_tt.dot(x.q));
    }
    if (form)
      S.gauss_jordan();
    S.vmult(lambda, rhs);
    for (unsigned int l = 0; l < m; ++l)
      rows->Y[l].add_to(a, lambda(l));
  }

  // (40): v* = v_prev + 2 dt a, q* = q + dt (v + v*)/2, then eta and mu.
  for (unsigned int i = 0; i < v_new.size(); ++i)
  {
    v_new[i] = x.v_prev[i] + 2. * h * a[i];
    q_new[i] = x.q[i] + 0.5 * h * (x.v[i] + v_new[i]);
  }
  if (m > 0)
  {
    dealii::FullMatrix<double>& S = rows->position_inverse;
    const bool form = rows->rigid_rows_move || S.m() != 2 * m;
    if (form)
      S.reinit(2 * m, 2 * m);
    dealii::Vector<double> rhs(2 * m), solution(2 * m);
    for (unsigned int k = 0; k < m; ++k)
    {
      const ConstraintState& s = s1[rigid[k]];
      for (unsigned int l = 0; form && l < m; ++l)
      {
        const auto &P = rows->P[l], &Q = rows->Q[l], &R = rows->R[l];
        const double GP = P.dot(s.G), GQ = Q.dot(s.G), GR = R.dot(s.G);
        const double GtP = P.dot(s.G_t), GtQ = Q.dot(s.G_t), GtR = R.dot(s.G_t);
        S(k, l) = h * h * GP + h * GQ;
        S(k, m + l) = h * GR;
        S(m + k, l) = h * h * GtP + h * GtQ + 2. * h * GP;
        S(m + k, m + l) = h * GtR;
      }
      rhs(k) = -s.G.dot(q_new);
      rhs(m + k) = -(s.G_t.dot(q_new) + s.G.dot(v_new));
    }
    if (form)
      S.gauss_jordan();
    S.vmult(solution, rhs);
    for (unsigned int l = 0; l < m; ++l)
    {
      const double eta = solution(l), mu = solution(m + l);
      rows->P[l].add_to(q_new, h * h * eta);
      rows->Q[l].add_to(q_new, h * eta);
      rows->R[l].add_to(q_new, h * mu);
      rows->P[l].add_to(v_new, 2. * h * eta);
    }
  }
  x.v_prev.swap(x.v); // v_{n} becomes v_prev
  x.v.swap(v_new);
  x.q.swap(q_new);
}

double growth_per_step(const SemiDiscreteSystem& system, const std::vector<bool>& active,
                       const double dt, const double t0, const unsigned int steps,
                       const ContactRows contact)
{
  HalfExplicitStepMap map(system, active, dt);
  const unsigned int n = system.n_dofs();
  HalfExplicitStepMap::State x;
  std::mt19937 random(17);
  std::uniform_real_distribution<double> uniform(-1., 1.);
  for (auto* y : {&x.q, &x.v, &x.v_prev})
  {
    y->reinit(n);
    for (auto& e : *y)
      e = uniform(random);
  }
  const double omega2 = 4. / (dt * dt);
  const auto norm = [&]()
  {
    // Four partial sums: one chain of additions would wait on each.
    double sum[4] = {0., 0., 0., 0.};
    for (unsigned int i = 0; i < n; ++i)
      sum[i % 4] +=
          omega2 * x.q[i] * x.q[i] + x.v[i] * x.v[i] + x.v_prev[i] * x.v_prev[i];
    return std::sqrt((sum[0] + sum[1]) + (sum[2] + sum[3]));
  };
  // log |x_k| accumulated with a normalisation every step; the growth is the
  // slope of its least-squares line over the second half (less sensitive to
  // the beating of the neutral modes than the ratio of two norms).
  double log_norm = 0.;
  const unsigned int first = steps / 2;
  double sk = 0., sy = 0., skk = 0., sky = 0.;
  for (unsigned int k = 0; k < steps; ++k)
  {
    const double t = contact == ContactRows::moving ? t0 + k * dt : t0;
    if (contact == ContactRows::moving)
      map.apply(t, t + 0.5 * dt, t + dt, x);
    else
      map.apply(t, t, t, x);
    const double size = norm();
    if (!(size > 0.) || !std::isfinite(size))
      return std::numeric_limits<double>::infinity();
    log_norm += std::log(size);
    const double scale = 1. / size;
    for (unsigned int i = 0; i < n; ++i)
    {
      x.q[i] *= scale;
      x.v[i] *= scale;
      x.v_prev[i] *= scale;
    }
    if (k >= first)
    {
      const double kk = k - first;
      sk += kk;
      sy += log_norm;
      skk += kk * kk;
      sky += kk * log_norm;
    }
  }
  const double count = steps - first;
  return std::exp((count * sky - sk * sy) / (count * skk - sk * sk));
}
} // namespace pantocat
