#include <pantocat/base/input_error.h>
#include <pantocat/time/bdf2_integrator.h>
#include <pantocat/time/dynamic_state_serialization.h>
#include <pantocat/constrained_fast/multiplier_system.h>

#include <algorithm>
#include <array>
#include <map>

namespace pantocat
{
namespace
{
using Levels = std::array<double, 3>;

/**
 * The rows g, dg/dt, d2g/dt2 of a constraint applied to a solution with
 * positions X, velocities c X - U1 and accelerations c (c X - U1) - U2, from
 * the dot products of the rows G, G_t, G_tt with X, U1 and U2: the
 * functionals of the multiplier system.
 */
Levels functionals(const double c, const double GX, const double GtX, const double GttX,
                   const double GU1, const double GtU1, const double GU2)
{
  const double Gv = c * GX - GU1, Gtv = c * GtX - GtU1, Ga = c * Gv - GU2;
  return {{GX, GtX + Gv, GttX + 2. * Gtv + Ga}};
}

/// g, dg/dt, d2g/dt2 of row @p r (offsets included) for the base solution @p B
/// with the history @p rho_q, @p rho_v.
Levels complete_levels(const ConstraintState& r, const double c,
                       const dealii::Vector<double>& B,
                       const dealii::Vector<double>& rho_q,
                       const dealii::Vector<double>& rho_v)
{
  // (a constant row's G_t, G_tt are empty: their products are +0)
  const bool moves = r.G_t.size() > 0 || r.G_tt.size() > 0;
  Levels L =
      functionals(c, r.G.dot(B), moves ? r.G_t.dot(B) : 0., moves ? r.G_tt.dot(B) : 0.,
                  r.G.dot(rho_q), moves ? r.G_t.dot(rho_q) : 0., r.G.dot(rho_v));
  L[0] += r.z;
  L[1] += r.z_t;
  L[2] += r.z_tt;
  return L;
}

/// Multiplier kinds: the columns of one constraint in its S batch, in the
/// order of the multiplier system (the fourth column is not used).
enum Column : unsigned int
{
  lambda = 0,
  eta = 1,
  mu = 2
};
/// Columns of the M batch: Y = M^-1 G^T, Z = M^-1 G_t^T.
enum MassColumn : unsigned int
{
  Y = 0,
  Z = 1
};
} // namespace

/// The block solver for one c: S = K + c D + c^2 M and the constraint columns.
struct Bdf2Integrator::Stage : IterationMatrix
{
  Stage(const SemiDiscreteSystem& system, const MassInverse& mass_inverse,
        const DampingOverMass& damping_over_mass, double c, LinearSolverType solver)
      : IterationMatrix(system, c, c * c, "BDF iteration matrix K + c D + c^2 M", solver),
        system(system), mass_inverse(mass_inverse), damping_over_mass(damping_over_mass),
        c(c)
  {
  }

  /// The right-hand side's operators of this c with the damping split
  /// (PatternOperators), for the BDF-2 steps.
  void split_damping()
  {
    split_operators = std::make_unique<PatternOperators>(
        system, PatternOperators::IterationFactors{c * c, c, 1.});
  }

  /**
   * The columns of a constraint with rows @p r: the S batch @p X
   * (X^lambda, X^eta, X^mu) and the M batch @p U (Y, Z), on the rows they
   * reach (LocalColumns).
   */
  void compute_columns(LocalColumns& X, LocalColumns& U, const ConstraintState& r)
  {
    X.clear();
    U.clear();
    U.add_row(Y, r.G, 1.);
    U.add_row(Z, r.G_t, 1.);
    // X^lambda = G^T, X^eta = G^T + c G_t^T + D Z, X^mu = c G^T + D Y before
    // S^-1, with D Z = D M^-1 G_t^T and D Y = D M^-1 G^T sparse where the
    // bodies allow it (DampingOverMass), else from Y and Z on full vectors.
    const bool sparse_damping =
        damping_over_mass.apply(r.G, DY) && damping_over_mass.apply(r.G_t, DZ);
    if (sparse_damping)
    {
      X.add_row(eta, DZ, 1.);
      X.add_row(mu, DY, 1.);
    }
    else
      add_damping_of_mass_columns(X, U);
    X.add_row(lambda, r.G, 1.);
    X.add_row(eta, r.G, 1.);
    X.add_row(eta, r.G_t, c);
    X.add_row(mu, r.G, c);
    X.solve(inverse);
    if (sparse_damping)
      mass_inverse.apply(U);
  }

  /// X^mu += D M^-1 G^T and X^eta += D M^-1 G_t^T from full vectors (U <- M^-1 U).
  void add_damping_of_mass_columns(LocalColumns& X, LocalColumns& U) const
  {
    const unsigned int n = system.n_dofs();
    mass_inverse.apply(U);
    dealii::Vector<double> u(n), Du(n);
    SparseRow entries;
    for (const unsigned int k : {Y, Z})
    {
      for (unsigned int i = 0; i < n; ++i)
        u[i] = U(i, k);
      system.damping.vmult(Du, u);
      entries.clear();
      for (unsigned int i = 0; i < n; ++i)
        if (Du[i] != 0.)
          entries.add(i, Du[i]);
      X.add_row(k == Y ? mu : eta, entries, 1.);
    }
  }

  /// The fixed constraints' block, once.
  void initialize_block(const std::vector<ConstraintState>& rows)
  {
    std::vector<const SparseRow*> G;
    std::vector<const Constraint*> constraints;
    for (const unsigned int i : fixed)
    {
      if (rows[i].G_t.size() > 0 || rows[i].G_tt.size() > 0)
        throw SimulationError("constraint " + system.constraints[i]->name() +
                              " has constant rows but a time derivative");
      G.push_back(&rows[i].G);
      constraints.push_back(system.constraints[i].get());
    }
    map_rows_to_fixed(G);
    block.initialize(G, constraints, inverse, mass_inverse, system.damping,
                     damping_over_mass, c, system.n_dofs());
    block_ready = true;
  }

  /// fixed_at_row from the rows @p G of the fixed constraints (block order).
  void map_rows_to_fixed(const std::vector<const SparseRow*>& G)
  {
    CompressedRows rows;
    for (const SparseRow* g : G)
      rows.push_back(*g);
    fixed_at_row.build(rows, system.n_dofs());
  }

  /**
   * The fixed rows @p in_block (with force or engaged) that the columns of
   * border constraint @p i reach, by the rows' entries (a dropper's row has
   * entries in the carrier's and the contact wire's blocks: its span is too
   * coarse a test), into @p list; @p slot (one entry per fixed constraint,
   * all -1) is workspace and left all -1.
   */
  void reached_fixed_rows(const unsigned int i, const std::vector<bool>& in_block,
                          std::vector<Reached>& list, std::vector<int>& slot) const
  {
    const auto [X, U] = batches(i);
    list.clear();
    const auto take = [&](const RowRanges& reach, const bool by_mass)
    {
      for (const RowRange& r : reach)
        for (unsigned int e = fixed_at_row.start[r.first]; e < fixed_at_row.start[r.last];
             ++e)
        {
          const unsigned int k = fixed_at_row.row[e];
          if (!in_block[k])
            continue;
          if (slot[k] < 0)
          {
            slot[k] = list.size();
            list.push_back({k, false, false});
          }
          (by_mass ? list[slot[k]].by_mass_columns : list[slot[k]].by_columns) = true;
        }
    };
    take(X->reach(), false);
    take(U->reach(), true);
    for (const Reached& f : list)
      slot[f.k] = -1;
  }

  /// The S and M batches of border constraint @p i (a moving one, or a
  /// touching fixed one: its columns computed on demand).
  std::pair<const LocalColumns*, const LocalColumns*> batches(const unsigned int i) const
  {
    if (moves[i])
      return {&S_columns[position[i]], &M_columns[position[i]]};
    const auto& [X, U] = touching_columns.at(i);
    return {&X, &U};
  }

  const SemiDiscreteSystem& system;
  const MassInverse& mass_inverse;
  const DampingOverMass& damping_over_mass;
  double c;
  /// With split_damping(): f + M h' + E r for this c (else the integrator's
  /// operators give f + M h + D r).
  std::unique_ptr<PatternOperators> split_operators;
  SparseRow DY, DZ; ///< workspace
  GglFixedBlock block;
  /// The fixed constraints (block order) with an entry in each row.
  RowsByColumn fixed_at_row;
  bool block_ready = false;
  /// Columns of the touching fixed constraints of the current step.
  std::map<unsigned int, std::pair<LocalColumns, LocalColumns>> touching_columns;
};

Bdf2Integrator::Bdf2Integrator(const SemiDiscreteSystem& system, const double time_step,
                               const unsigned int max_iterations,
                               const LinearSolverType linear_solver)
    : TimeIntegrator(system), dt(time_step), linear_solver(linear_solver),
      damping_over_mass(system), operators(system), at_next(system),
      active_set(system, max_iterations), impacts(system, mass_inverse),
      work(std::make_unique<TrialWorkspace>())
{
  mass_inverse.initialize(system.mass, system.mass_is_diagonal, "mass matrix M",
                          linear_solver);
}

Bdf2Integrator::~Bdf2Integrator() = default;

namespace
{
/// A border unknown (kind: lambda, eta, mu) or equation (level 0, 1, 2 or
/// force_law) of one constraint.
struct Slot
{
  unsigned int constraint, kind;
};
constexpr unsigned int force_law = 3; ///< the equation of an engaged spring

/// Status of a constraint in a trial of the active-set iteration.
enum class Role : char
{
  none,
  force,    ///< active with force: lambda, eta, mu; levels 2, 0, 1
  touching, ///< holds without force: eta, mu; levels 0, 1
  engaged   ///< an engaged compliant constraint: lambda; its law
};
} // namespace

/// The vectors of implicit_step() and solve_trial(), kept from step to step
/// so that a step allocates nothing once their sizes are reached.
struct Bdf2Integrator::TrialWorkspace
{
  std::vector<double> gaps, rates;
  std::vector<Role> role;
  /// Per border constraint: the fixed rows its columns reach.
  std::vector<std::vector<Reached>> near;
  std::vector<int> near_slot; ///< workspace: a fixed row's place in its near list
  std::vector<bool> in_block; ///< per fixed constraint: with force or engaged
  /// Per constraint: held at every history point of the step; per fixed
  /// constraint: settled in the trial (GglFixedBlock::select()).
  std::vector<bool> settled_at_start, settled;
  std::vector<bool> force, engaged;
  std::vector<Slot> unknowns, equations;
  std::vector<unsigned int> border;
  dealii::Vector<double> r, y, rhs;
  std::vector<dealii::Vector<double>> Bc, Cr;
  dealii::FullMatrix<double> D;
  std::vector<double> X0, X1, X2, V0, V1, V2, Y0, Y1;
  std::vector<dealii::Vector<double>*> batch;
  /// The local solve's sources (GglFixedBlock::local_subset()) and the
  /// fixed columns that reach a border row.
  std::vector<unsigned int> sources, reached_by_row;
  std::vector<double> lambda_eta, eta_F, mu_F;
  RowRanges reach, reach_scratch;
};

DynamicState Bdf2Integrator::implicit_step(Stage& s, const dealii::Vector<double>& rho_q,
                                           const dealii::Vector<double>& rho_v,
                                           const double t1,
                                           const std::vector<bool>& active_at_start,
                                           const std::vector<bool>* held_before,
                                           DynamicState storage)
{
  const unsigned int m_all = system.n_constraints();
  const double c = s.c;
  const auto& rows = at_next.at(t1);
  if (!s.block_ready)
    s.initialize_block(rows);
  // Base solution S^-1 (f + M history + D rho_q); the moving constraints'
  // columns on the rows they reach.
  const PatternOperators& ops = s.split_operators ? *s.split_operators : operators;
  ops.set_time(t1);
  ops.solve_history(history, rho_q, s.inverse, s.base);
  for (unsigned int k = 0; k < s.moving.size(); ++k)
    s.compute_columns(s.S_columns[k], s.M_columns[k], rows[s.moving[k]]);
  s.touching_columns.clear();
  const dealii::Vector<double>& B = s.base;

  std::vector<bool>& settled = work->settled_at_start;
  settled.resize(m_all);
  for (unsigned int k = 0; k < m_all; ++k)
    settled[k] = settling && held_before && active_at_start[k] && (*held_before)[k];

  // The levels g, dg/dt, d2g/dt2 of the base solution on every row; of a
  // constant row that may be settled, g alone (the block reads no more of a
  // settled one; solve_trial() completes them where a trial needs them).
  base_levels.resize(m_all);
  levels_complete.resize(m_all);
  for (unsigned int k = 0; k < m_all; ++k)
  {
    const ConstraintState& r = rows[k];
    // (a constant row's G_t, G_tt are empty: their products are +0)
    const bool moves = r.G_t.size() > 0 || r.G_tt.size() > 0;
    levels_complete[k] = moves || !settled[k];
    if (levels_complete[k])
      base_levels[k] = complete_levels(r, c, B, rho_q, rho_v);
    else
      base_levels[k] = {{r.G.dot(B) + r.z, 0., 0.}};
  }

  // Active-set iteration (Sec. 5.3): each trial solves the multiplier system
  // (the fixed block bordered by the moving and touching constraints) and
  // assembles q, v, a; its gaps and rates decide.
  DynamicState x = std::move(storage); // its vectors' memory, if any
  x.t = t1;
  x.impulse.clear();
  std::vector<double>&gaps = work->gaps, &rates = work->rates;
  gaps.resize(m_all);
  rates.resize(m_all);
  active_set.start(active_at_start);
  for (;;)
  {
    solve_trial(s, rows, rho_q, rho_v, x);
    for (unsigned int k = 0; k < m_all; ++k)
    {
      // (only those accept() reads: an active rigid one's are not)
      gaps[k] = active_set.reads_gap(k) ? rows[k].position_residual(x.q) : 0.;
      rates[k] = active_set.reads_rate(k) ? rows[k].velocity_residual(x.q, x.v) : 0.;
    }
    if (active_set.accept(gaps, x.lambda, t1, step_number + 1, rates))
      break;
    ++stats.active_set_iterations;
    // the trial took the base's vector for q: solved again, the same bits
    ops.solve_history(history, rho_q, s.inverse, s.base);
  }
  stats.active_set_changes += active_set.changes_in_step();
  x.active = active_set.active();
  clamp_compliant_forces(system, x.lambda);
  // A constraint that closed in the step (taken without it): the impact at
  // t_{n+1}, by projection; P is its impulse.
  if (active_set.impact_in_step())
  {
    ImpactProjection::Result r =
        impacts.project(rows, active_set.holding_indices(), t1, x.lambda, dt, x.q, x.v);
    x.impulse.swap(r.impulse);
    for (const unsigned int i : r.separated)
      x.active[i] = false, x.lambda[i] = 0.;
  }
  return x;
}

namespace
{
/// a + b entry by entry; an empty vector counts as zeros.
std::vector<double> combined_impulses(const std::vector<double>& a, const double fa,
                                      const std::vector<double>& b, const double fb)
{
  if (a.empty() && b.empty())
    return {};
  std::vector<double> sum(std::max(a.size(), b.size()), 0.);
  for (unsigned int i = 0; i < a.size(); ++i)
    sum[i] += fa * a[i];
  for (unsigned int i = 0; i < b.size(); ++i)
    sum[i] += fb * b[i];
  return sum;
}

/**
 * The BDF-2 history in one pass: rho_q = f q + fp q_prev, rho_v = f v +
 * fp v_prev and h = rho_v + c rho_q (compiled for AVX2 beside the baseline;
 * no fused multiply-add, so the same bits either way).
 */
__attribute__((target_clones("avx2", "default"))) void
bdf2_history(const unsigned int n, const double f, const double fp, const double c,
             const double* __restrict q, const double* __restrict q_prev,
             const double* __restrict v, const double* __restrict v_prev,
             double* __restrict rho_q, double* __restrict rho_v, double* __restrict h)
{
  for (unsigned int i = 0; i < n; ++i)
  {
    const double rq = f * q[i] + fp * q_prev[i], rv = f * v[i] + fp * v_prev[i];
    rho_q[i] = rq;
    rho_v[i] = rv;
    h[i] = rv + c * rq;
  }
}

/// h = rho_v + c rho_q (the Richardson start's steps).
__attribute__((target_clones("avx2", "default"))) void
euler_history(const unsigned int n, const double c, const double* __restrict rho_q,
              const double* __restrict rho_v, double* __restrict h)
{
  for (unsigned int i = 0; i < n; ++i)
    h[i] = rho_v[i] + c * rho_q[i];
}
} // namespace

namespace
{
/**
 * solve_bordered() for border columns @p B and rows @p C with entries on the
 * slots of @p block's local_members() alone (GglFixedBlock::local_subset()): r is solved
 * whole, the border columns on the subset (GglFixedBlock::solve_local()), and
 * the products C Z, C x0 and x0 - Z y are formed there. B and C are set to
 * zero on return (on the subset's slots, where they have entries).
 */
void solve_bordered_locally(GglFixedBlock& block, std::vector<dealii::Vector<double>>& B,
                            std::vector<dealii::Vector<double>>& C,
                            dealii::FullMatrix<double>& D, dealii::Vector<double>& r,
                            dealii::Vector<double>& s, dealii::Vector<double>& rhs,
                            std::vector<dealii::Vector<double>*>& batch, const double t)
{
  const unsigned int p = s.size();
  const std::vector<unsigned int>& subset = block.local_members();
  block.solve({&r});
  batch.clear();
  for (auto& b : B)
  {
    bool nonzero = false;
    for (const unsigned int k : subset)
      nonzero = nonzero || b[3 * k] != 0. || b[3 * k + 1] != 0. || b[3 * k + 2] != 0.;
    if (nonzero)
      batch.push_back(&b);
  }
  block.solve_local(batch);
  // The products over the subset's slots (C is zero off them, and so is Z).
  const auto product =
      [&](const dealii::Vector<double>& a, const dealii::Vector<double>& b)
  {
    double sum = 0.;
    for (const unsigned int k : subset)
      sum +=
          a[3 * k] * b[3 * k] + a[3 * k + 1] * b[3 * k + 1] + a[3 * k + 2] * b[3 * k + 2];
    return sum;
  };
  rhs = s;
  for (unsigned int k = 0; k < p; ++k)
  {
    rhs(k) -= product(C[k], r);
    for (unsigned int l = 0; l < p; ++l)
      D(k, l) -= product(C[k], B[l]);
  }
  solve_multiplier_system(D, rhs, s, t, "BDF step");
  for (unsigned int l = 0; l < p; ++l)
    for (const unsigned int k : subset)
      for (unsigned int j = 3 * k; j < 3 * k + 3; ++j)
      {
        r[j] -= s(l) * B[l][j];
        B[l][j] = 0.;
        C[l][j] = 0.;
      }
}
} // namespace

void Bdf2Integrator::solve_trial(Stage& s, const std::vector<ConstraintState>& rows,
                                 const dealii::Vector<double>& rho_q,
                                 const dealii::Vector<double>& rho_v, DynamicState& x)
{
  const unsigned int n = system.n_dofs(), m_all = system.n_constraints(),
                     mF = s.fixed.size();
  const double c = s.c;
  // Roles; fixed constraints with force or engaged form the block, the
  // moving ones and the touching fixed ones border it.
  TrialWorkspace& w = *work;
  std::vector<Role>& role = w.role;
  role.assign(m_all, Role::none);
  for (const unsigned int i : active_set.active_indices())
    role[i] = Role::touching;
  for (const unsigned int i : active_set.force_indices())
    role[i] = Role::force;
  for (const unsigned int i : active_set.engaged_indices())
    role[i] = Role::engaged;
  std::vector<bool>&force = w.force, &engaged = w.engaged;
  force.assign(mF, false);
  engaged.assign(mF, false);
  std::vector<Slot>&unknowns = w.unknowns, &equations = w.equations;
  unknowns.clear();
  equations.clear();
  std::vector<unsigned int>& border = w.border;
  border.clear();
  for (unsigned int i = 0; i < m_all; ++i)
  {
    if (role[i] == Role::none)
      continue;
    const bool moving = s.moves[i];
    if (!moving && role[i] != Role::touching)
    {
      (role[i] == Role::force ? force : engaged)[s.position[i]] = true;
      continue;
    }
    border.push_back(i);
    if (role[i] == Role::force)
      unknowns.insert(unknowns.end(), {{i, lambda}, {i, eta}, {i, mu}}),
          equations.insert(equations.end(), {{i, 2}, {i, 0}, {i, 1}});
    else if (role[i] == Role::touching)
      unknowns.insert(unknowns.end(), {{i, eta}, {i, mu}}),
          equations.insert(equations.end(), {{i, 0}, {i, 1}});
    else
      unknowns.push_back({i, lambda}), equations.push_back({i, force_law});
    if (!moving && !s.touching_columns.count(i))
    {
      auto& [X, U] = s.touching_columns[i];
      X.reinit(n);
      U.reinit(n);
      s.compute_columns(X, U, rows[i]);
    }
  }
  // The fixed rows in the block that each border constraint's columns reach.
  std::vector<std::vector<Reached>>& near = w.near;
  near.resize(border.size());
  std::vector<bool>& in_block = w.in_block;
  in_block.resize(mF);
  for (unsigned int k = 0; k < mF; ++k)
    in_block[k] = force[k] || engaged[k];
  w.near_slot.assign(mF, -1);
  for (std::size_t b = 0; b < border.size(); ++b)
    s.reached_fixed_rows(border[b], in_block, near[b], w.near_slot);
  // Settled: held at the history points and out of the reach of the border's
  // mass columns, whose mu and eta (moving contacts, touching constraints)
  // would otherwise change its levels 1 and 2 (GglFixedBlock::select()).
  std::vector<bool>& settled = w.settled;
  settled.assign(mF, false);
  for (unsigned int k = 0; k < mF; ++k)
    settled[k] = force[k] && w.settled_at_start[s.fixed[k]];
  for (std::size_t b = 0; b < border.size(); ++b)
    if (role[border[b]] != Role::engaged)
      for (const Reached& f : near[b])
        settled[f.k] = settled[f.k] && !f.by_mass_columns;
  s.block.select(force, engaged, settled);
  settled_count = s.block.n_settled();
  const unsigned int p = unknowns.size();

  // Levels of row k against the column of border unknown u.
  const auto border_levels = [&](const unsigned int k, const Slot& u)
  {
    const auto [X, U] = s.batches(u.constraint);
    const ConstraintState& r = rows[k];
    const double GY = U->dot(r.G, Y), GtY = U->dot(r.G_t, Y), GZ = U->dot(r.G, Z),
                 GtZ = U->dot(r.G_t, Z);
    const unsigned int kind = u.kind;
    return functionals(c, X->dot(r.G, kind), X->dot(r.G_t, kind), X->dot(r.G_tt, kind),
                       kind == eta  ? GZ
                       : kind == mu ? GY
                                    : 0.,
                       kind == eta  ? GtZ
                       : kind == mu ? GtY
                                    : 0.,
                       kind == eta ? GY : 0.);
  };
  const auto value = [&](const Levels& L, const Slot& e)
  {
    return e.kind == force_law
               ? L[0] + damping_ratio(*system.constraints[e.constraint]) * L[1]
               : L[e.kind];
  };
  // The fixed rows in the block's equation slots (GglFixedBlock).
  const auto fixed_slots =
      [&](const unsigned int k, const Levels& L, dealii::Vector<double>& v)
  {
    if (force[k])
    {
      v[3 * k + 1] = L[0];
      v[3 * k + 2] = L[1] - c * L[0];
      v[3 * k] = L[2] - c * L[1];
    }
    else if (engaged[k])
      v[3 * k] = L[0] + s.block.damping_ratio(k) * L[1];
  };

  dealii::Vector<double>&r = w.r, &y = w.y;
  r.reinit(3 * mF);
  y.reinit(p);
  // The base levels of a row, completed if implicit_step() left them at g.
  const auto levels_of = [&](const unsigned int i) -> const Levels&
  {
    if (!levels_complete[i])
    {
      base_levels[i] = complete_levels(rows[i], c, s.base, rho_q, rho_v);
      levels_complete[i] = true;
    }
    return base_levels[i];
  };
  for (unsigned int k = 0; k < mF; ++k)
  {
    if (force[k] && !s.block.has_eta_mu(k)) // settled: the block reads g alone
      r[3 * k + 1] = -base_levels[s.fixed[k]][0];
    else if (force[k] || engaged[k])
    {
      const Levels& g = levels_of(s.fixed[k]);
      fixed_slots(k, {{-g[0], -g[1], -g[2]}}, r);
    }
  }
  // Bc and Cr are zero between trials (set back on the slots they used).
  std::vector<dealii::Vector<double>>&Bc = w.Bc, &Cr = w.Cr;
  Bc.resize(p);
  Cr.resize(p);
  for (unsigned int u = 0; u < p; ++u)
    for (dealii::Vector<double>* v : {&Bc[u], &Cr[u]})
      if (v->size() != 3 * mF)
        v->reinit(3 * mF);
  dealii::FullMatrix<double>& D = w.D;
  D.reinit(p, p);
  // Fixed rows against the border columns: G_t = G_tt = 0 on them, and the
  // unknowns of one border constraint share its batches, so each fixed row
  // takes its products with them once (the values border_levels() gives).
  for (unsigned int u0 = 0, u1 = 0, b = 0; u0 < p; u0 = u1, ++b)
  {
    while (u1 < p && unknowns[u1].constraint == unknowns[u0].constraint)
      ++u1;
    const auto [X, U] = s.batches(unknowns[u0].constraint);
    // Rows the columns do not reach keep their zeros (their products are +0).
    for (const Reached& f : near[b])
    {
      const unsigned int k = f.k;
      const SparseRow& G = rows[s.fixed[k]].G;
      const std::array<double, InterleavedColumns::width>
          GX =
              f.by_columns ? X->dots(G) : std::array<double, InterleavedColumns::width>{},
          GU = f.by_mass_columns ? U->dots(G)
                                 : std::array<double, InterleavedColumns::width>{};
      for (unsigned int u = u0; u < u1; ++u)
      {
        const unsigned int kind = unknowns[u].kind;
        fixed_slots(k,
                    functionals(c, GX[kind], 0., 0.,
                                kind == eta  ? GU[Z]
                                : kind == mu ? GU[Y]
                                             : 0.,
                                0., kind == eta ? GU[Y] : 0.),
                    Bc[u]);
      }
    }
  }
  // Border rows against the fixed unknowns, from the truncated columns.
  const GglFixedBlock& block = s.block;
  std::vector<double>&X0 = w.X0, &X1 = w.X1, &X2 = w.X2, &V0 = w.V0, &V1 = w.V1,
  &V2 = w.V2, &Y0 = w.Y0, &Y1 = w.Y1;
  // The fixed rows that a border column or row reaches: the sources of the
  // local solve (GglFixedBlock::local_subset()).
  std::vector<unsigned int>& sources = w.sources;
  sources.clear();
  for (std::size_t b = 0; b < border.size(); ++b)
    for (const Reached& f : near[b])
      sources.push_back(f.k);
  unsigned int products_of = m_all;
  std::vector<unsigned int>& reached_by_row = w.reached_by_row;
  for (unsigned int e = 0; e < p; ++e)
  {
    const Slot& eq = equations[e];
    const ConstraintState& row = rows[eq.constraint];
    if (products_of != eq.constraint)
    {
      const TruncatedColumns& X = block.stiffness_columns();
      X.row_products(row.G, X0);
      X.row_products(row.G_t, X1);
      X.row_products(row.G_tt, X2);
      X.partner_row_products(row.G, V0);
      X.partner_row_products(row.G_t, V1);
      X.partner_row_products(row.G_tt, V2);
      block.mass_columns().row_products(row.G, Y0);
      block.mass_columns().row_products(row.G_t, Y1);
      products_of = eq.constraint;
      // The fixed columns that reach this row (the others' entries stay 0).
      reached_by_row.clear();
      for (unsigned int l = 0; l < mF; ++l)
        if ((force[l] || engaged[l]) &&
            (X0[l] != 0. || X1[l] != 0. || X2[l] != 0. || V0[l] != 0. || V1[l] != 0. ||
             V2[l] != 0. || Y0[l] != 0. || Y1[l] != 0.))
          reached_by_row.push_back(l);
      sources.insert(sources.end(), reached_by_row.begin(), reached_by_row.end());
    }
    for (const unsigned int l : reached_by_row)
    {
      Cr[e][3 * l] = value(functionals(c, X0[l], X1[l], X2[l], 0., 0., 0.), eq);
      if (!force[l] || !block.has_eta_mu(l)) // a settled one's eta, mu are 0
        continue;
      Cr[e][3 * l + 1] = value(functionals(c, X0[l], X1[l], X2[l], 0., 0., Y0[l]), eq);
      Cr[e][3 * l + 2] = value(functionals(c, V0[l], V1[l], V2[l], Y0[l], Y1[l], 0.), eq);
    }
    for (unsigned int u = 0; u < p; ++u)
    {
      D(e, u) = value(border_levels(eq.constraint, unknowns[u]), eq);
      if (eq.kind == force_law && unknowns[u].constraint == eq.constraint)
        D(e, u) += 1. / system.constraints[eq.constraint]->compliance().stiffness;
    }
    y(e) = -value(levels_of(eq.constraint), eq);
  }
  dealii::Vector<double>& rhs = w.rhs;
  std::vector<dealii::Vector<double>*>& batch = w.batch;
  std::sort(sources.begin(), sources.end());
  sources.erase(std::unique(sources.begin(), sources.end()), sources.end());
  local_size = 0;
  if (p > 0 && mF > 0 && border_locally && s.block.local_subset(sources))
  {
    solve_bordered_locally(s.block, Bc, Cr, D, r, y, rhs, batch, x.t);
    local_size = s.block.local_members().size();
  }
  else
  {
    solve_bordered([&](const auto& xs) { block.solve(xs); }, Bc, Cr, D, r, y, rhs, batch,
                   x.t, "BDF step");
    for (unsigned int u = 0; u < p; ++u)
    {
      Bc[u] = 0.;
      Cr[u] = 0.;
    }
  }

  // The multipliers, and
  //   q = base + sum_l lambda_l X^lambda_l + eta_l X^eta_l + mu_l X^mu_l,
  //   v = c q - rho_q - sum_l (mu_l Y_l + eta_l Z_l),  a = c v - rho_v - sum_l eta_l Y_l
  // (fixed: X^eta = X^lambda, Z = 0).
  x.lambda.assign(m_all, 0.);
  std::vector<double>&lambda_eta = w.lambda_eta, &eta_F = w.eta_F, &mu_F = w.mu_F;
  lambda_eta.resize(mF);
  eta_F.resize(mF);
  mu_F.resize(mF);
  for (unsigned int k = 0; k < mF; ++k)
  {
    x.lambda[s.fixed[k]] = r[3 * k];
    lambda_eta[k] = r[3 * k] + r[3 * k + 1];
    eta_F[k] = r[3 * k + 1];
    mu_F[k] = r[3 * k + 2];
  }
  for (unsigned int u = 0; u < p; ++u)
    if (unknowns[u].kind == lambda)
      x.lambda[unknowns[u].constraint] = y(u);

  // q takes the base's vector (no copy; implicit_step() solves for the base
  // again before another trial). q, v, a are formed from the base and the
  // fixed forces' sums in combine_trial()'s pass (no zeroing), unless
  // add_forces() adds them first: by solves (many constraints close together
  // on a FEM grid) or when their sums reach many short stretches of rows.
  const bool forces_added_first = mF > 0 && !block.sums_in_one_pass();
  GglFixedBlock::ForceSums sums;
  x.q.swap(s.base);
  if (forces_added_first)
  {
    x.v.reinit(n);
    x.a.reinit(n);
    block.add_forces(lambda_eta, eta_F, mu_F, x.q, x.v, x.a); // x.v, x.a: u1, u2
  }
  else
  {
    for (dealii::Vector<double>* y : {&x.v, &x.a})
      y->reinit(n, true);
    if (mF > 0)
      sums = block.sum_forces(lambda_eta, eta_F, mu_F);
  }
  // The border columns, then v and a, in one pass; on each unknown the
  // border unknowns add in their order.
  border_terms.clear();
  RowRanges& reach = w.reach;
  reach.clear();
  for (unsigned int u = 0; u < p; ++u)
  {
    const auto [X, U] = s.batches(unknowns[u].constraint);
    if (u == 0 || unknowns[u].constraint != unknowns[u - 1].constraint)
    {
      add_ranges(reach, X->reach(), w.reach_scratch);
      add_ranges(reach, U->reach(), w.reach_scratch);
    }
    const unsigned int kind = unknowns[u].kind;
    const double f = y(u);
    border_terms.push_back({X->data() + kind, U->data(), f, kind == mu ? f : 0.,
                            kind == eta ? f : 0., kind == eta ? f : 0.});
  }
  combine_trial(border_terms, reach, c, rho_q, rho_v, !forces_added_first,
                mF > 0 && !forces_added_first ? &sums : nullptr,
                &s == bdf2.get() ? next_history : nullptr, x);
}

namespace
{
/**
 * The next step's history on a block's rows, formed in the step's last pass
 * from the q_{n+1}, v_{n+1} it has just stored: rho_q' = f q_{n+1} + fp q_n,
 * rho_v' = f v_{n+1} + fp v_n, h' = rho_v' + kappa rho_q' (kappa = c + mu of
 * the block), each entry as bdf2_history() forms it at the next step.
 */
struct NextPiece
{
  const double* q_n = nullptr;
  const double* v_n = nullptr;
  double f = 0., fp = 0., kappa = 0.;
  double *rho_q = nullptr, *rho_v = nullptr, *h = nullptr;
};

/// @p pass(piece, next) on the pieces of @p rows in each block of @p next's
/// (all of @p rows with an empty NextPiece without @p next).
template <typename Pass>
void by_blocks(const Bdf2Integrator::NextHistory* next, const RowRange rows,
               const Pass& pass)
{
  if (!next)
    return pass(rows, NextPiece{});
  for (const PatternOperators::Shift& b : *next->blocks)
  {
    const int first = std::max<int>(rows.first, b.first),
              last = std::min<int>(rows.last, b.last);
    if (first < last)
      pass(RowRange{first, last},
           NextPiece{next->q_n, next->v_n, next->f, next->fp, next->c + b.mu, next->rho_q,
                     next->rho_v, next->h});
  }
}

/**
 * q, v, a += P border terms (Bdf2Integrator::BorderTerm) in one pass; in the
 * last pass also v = c q - rho_q - v, a = c v - rho_v - a. Without branches:
 * a term's mass columns enter with factors that are 0 where its kind has
 * none; v and a are never -0 (they start at +0 and take sums that start at
 * +0), so adding 0 U leaves them as they are.
 */
template <unsigned int P, bool last, typename Term, bool next = false>
__attribute__((target_clones("avx2", "default"))) void
combine_pass(const Term* terms, const double c, const double* __restrict rq,
             const double* __restrict rv, const RowRange rows, double* __restrict q,
             double* __restrict v, double* __restrict a, const NextPiece nx = {})
{
  // The next history's arrays as restricted locals (GCC does not take the
  // restriction of a struct's members): the loop stays vectorised.
  const double* __restrict q_n = nx.q_n;
  const double* __restrict v_n = nx.v_n;
  double* __restrict next_rq = nx.rho_q;
  double* __restrict next_rv = nx.rho_v;
  double* __restrict next_h = nx.h;
  constexpr unsigned int w = InterleavedColumns::width;
  const double* X[P > 0 ? P : 1];
  const double* U[P > 0 ? P : 1];
  double f[P > 0 ? P : 1], vY[P > 0 ? P : 1], vZ[P > 0 ? P : 1], aY[P > 0 ? P : 1];
  for (unsigned int k = 0; k < P; ++k)
  {
    X[k] = terms[k].X;
    U[k] = terms[k].U;
    f[k] = terms[k].f;
    vY[k] = terms[k].v_Y;
    vZ[k] = terms[k].v_Z;
    aY[k] = terms[k].a_Y;
  }
  for (int i = rows.first; i < rows.last; ++i)
  {
    double qi = q[i], vi = v[i], ai = a[i];
    for (unsigned int k = 0; k < P; ++k)
    {
      qi += f[k] * X[k][w * i];
      vi += vY[k] * U[k][w * i + Y];
      vi += vZ[k] * U[k][w * i + Z];
      ai += aY[k] * U[k][w * i + Y];
    }
    q[i] = qi;
    if (last)
    {
      vi = c * qi - rq[i] - vi;
      ai = c * vi - rv[i] - ai;
    }
    v[i] = vi;
    a[i] = ai;
    if (next)
    {
      const double rq2 = nx.f * qi + nx.fp * q_n[i], rv2 = nx.f * vi + nx.fp * v_n[i];
      next_rq[i] = rq2;
      next_rv[i] = rv2;
      next_h[i] = rv2 + nx.kappa * rq2;
    }
  }
}

/**
 * On @p rows: q = base (which q holds on entry), + q1, then + q2 where they
 * reach; u1 = 0 (+ y1), u2 = 0 (+ y2) where the fixed forces' mass sums
 * reach; the sums read are set to 0. With @p last (rows off the border's
 * reach), also v = c q - rho_q - u1, a = c v - rho_v - u2, and with @p next
 * the next step's history (NextPiece); else v = u1, a = u2 for the border
 * passes. Each entry as the zeroing, the additions of the sums and
 * combine_pass<0, true>() made it (x - (+0) = x where a sum does not reach).
 */
template <bool with_q1, bool with_q2, bool with_u, bool last, bool next>
__attribute__((target_clones("avx2", "default"))) void
form_pass(double* __restrict q1, double* __restrict q2, double* __restrict y1,
          double* __restrict y2, const double c, const double* __restrict rq,
          const double* __restrict rv, const RowRange rows, double* __restrict q,
          double* __restrict v, double* __restrict a, const NextPiece nx)
{
  const double* __restrict q_n = nx.q_n; // as in combine_pass()
  const double* __restrict v_n = nx.v_n;
  double* __restrict next_rq = nx.rho_q;
  double* __restrict next_rv = nx.rho_v;
  double* __restrict next_h = nx.h;
  for (int i = rows.first; i < rows.last; ++i)
  {
    double qi = q[i], u1 = 0., u2 = 0.;
    if (with_q1)
    {
      qi += q1[i];
      q1[i] = 0.;
    }
    if (with_q2)
    {
      qi += q2[i];
      q2[i] = 0.;
    }
    if (with_u)
    {
      u1 += y1[i];
      u2 += y2[i];
      y1[i] = 0.;
      y2[i] = 0.;
    }
    q[i] = qi;
    if (last)
    {
      const double vi = with_u ? c * qi - rq[i] - u1 : c * qi - rq[i];
      v[i] = vi;
      a[i] = with_u ? c * vi - rv[i] - u2 : c * vi - rv[i];
      if (next)
      {
        const double rq2 = nx.f * qi + nx.fp * q_n[i], rv2 = nx.f * vi + nx.fp * v_n[i];
        next_rq[i] = rq2;
        next_rv[i] = rv2;
        next_h[i] = rv2 + nx.kappa * rq2;
      }
    }
    else
    {
      v[i] = u1;
      a[i] = u2;
    }
  }
}

/// form_pass() with its template arguments from @p flag.
template <bool... Known>
void form_pass_for(const std::array<bool, 5>& flag, double* q1, double* q2, double* y1,
                   double* y2, const double c, const double* rq, const double* rv,
                   const RowRange rows, double* q, double* v, double* a,
                   const NextPiece& nx)
{
  constexpr std::size_t k = sizeof...(Known);
  if constexpr (k == 5)
  {
    constexpr std::array<bool, 5> known{{Known...}};
    if constexpr (known[3] || !known[4]) // a next history on the last pass only
      form_pass<Known...>(q1, q2, y1, y2, c, rq, rv, rows, q, v, a, nx);
  }
  else if (flag[k])
    form_pass_for<Known..., true>(flag, q1, q2, y1, y2, c, rq, rv, rows, q, v, a, nx);
  else
    form_pass_for<Known..., false>(flag, q1, q2, y1, y2, c, rq, rv, rows, q, v, a, nx);
}

/// Walks sorted disjoint ranges (or none) along increasing rows: inside()
/// says whether a row lies in one; next() is the first boundary above a row.
class RangeWalk
{
public:
  explicit RangeWalk(const RowRanges* ranges) : r(ranges) {}
  bool inside(const int row)
  {
    advance(row);
    return r && k < r->size() && (*r)[k].first <= row;
  }
  int next(const int row, const int end)
  {
    advance(row);
    if (!r || k == r->size())
      return end;
    return (*r)[k].first > row ? (*r)[k].first : (*r)[k].last;
  }

private:
  void advance(const int row)
  {
    while (r && k < r->size() && (*r)[k].last <= row)
      ++k;
  }
  const RowRanges* r;
  std::size_t k = 0;
};
} // namespace

void Bdf2Integrator::combine_trial(const std::vector<BorderTerm>& terms,
                                   const RowRanges& reach, const double c,
                                   const dealii::Vector<double>& rho_q,
                                   const dealii::Vector<double>& rho_v,
                                   const bool from_base,
                                   const GglFixedBlock::ForceSums* sums,
                                   const NextHistory* next, DynamicState& x)
{
  const int n = x.q.size();
  double *q = x.q.begin(), *v = x.v.begin(), *a = x.a.begin();
  const double *rq = rho_q.begin(), *rv = rho_v.begin();
  if (from_base)
  {
    // Stretches of rows on which the border's reach and the rows of each sum
    // do not change: q, v, a from the base and the sums, all of it off the
    // reach, one pass.
    RangeWalk on_reach(&reach), in_q1(sums ? sums->q.first_rows : nullptr),
        in_q2(sums ? sums->q.second_rows : nullptr),
        in_u(sums ? sums->u.first_rows : nullptr);
    double *q1 = sums ? sums->q.first : nullptr, *q2 = sums ? sums->q.second : nullptr,
           *y1 = sums ? sums->u.first : nullptr, *y2 = sums ? sums->u.second : nullptr;
    for (int first = 0; first < n;)
    {
      const int last = std::min({on_reach.next(first, n), in_q1.next(first, n),
                                 in_q2.next(first, n), in_u.next(first, n)});
      const bool off_reach = !on_reach.inside(first);
      const std::array<bool, 5> flag{{in_q1.inside(first), in_q2.inside(first),
                                      in_u.inside(first), off_reach,
                                      next != nullptr && off_reach}};
      by_blocks(off_reach ? next : nullptr, RowRange{first, last},
                [&](const RowRange piece, const NextPiece& nx) {
                  form_pass_for<>(flag, q1, q2, y1, y2, c, rq, rv, piece, q, v, a, nx);
                });
      first = last;
    }
  }
  // On the rows the terms reach, passes of three terms (a contact with
  // force: lambda, eta, mu); then v and a on all rows. On each unknown the
  // terms add in their order (off the reach they are zero).
  for (const RowRange& rows : reach)
    for (std::size_t k = 0; k < terms.size(); k += 3)
      switch (std::min<std::size_t>(3, terms.size() - k))
      {
      case 1:
        combine_pass<1, false>(terms.data() + k, c, rq, rv, rows, q, v, a);
        break;
      case 2:
        combine_pass<2, false>(terms.data() + k, c, rq, rv, rows, q, v, a);
        break;
      default:
        combine_pass<3, false>(terms.data() + k, c, rq, rv, rows, q, v, a);
      }
  // The last pass, and with @p next the next step's history on its rows.
  const auto last_pass = [&](const RowRange rows)
  {
    by_blocks(next, rows,
              [&](const RowRange piece, const NextPiece& nx)
              {
                if (next)
                  combine_pass<0, true, BorderTerm, true>(terms.data(), c, rq, rv, piece,
                                                          q, v, a, nx);
                else
                  combine_pass<0, true>(terms.data(), c, rq, rv, piece, q, v, a);
              });
  };
  if (!from_base)
    last_pass(RowRange{0, n});
  else
    for (const RowRange& rows : reach)
      last_pass(rows);
}

void Bdf2Integrator::form_history(const double c, const dealii::Vector<double>& rho_q,
                                  const dealii::Vector<double>& rho_v)
{
  const unsigned int n = system.n_dofs();
  history.reinit(n, true);
  euler_history(n, c, rho_q.begin(), rho_v.begin(), history.begin());
}

void Bdf2Integrator::initialize(const DynamicState& initial)
{
  current = initial;
  current.impulse.clear();
  previous = DynamicState();
  step_number = 0;
  restart = false;
  history_ready = false;
}

void Bdf2Integrator::richardson_start()
{
  history_ready = false;
  // Backward Euler with dt, and twice with dt/2; extrapolate (2nd order), Sec. 5.2.
  const DynamicState x0 = current;
  if (!start_full) // kept: a restart after an impact uses them again
  {
    start_full = std::make_unique<Stage>(system, mass_inverse, damping_over_mass, 1. / dt,
                                         linear_solver);
    start_half = std::make_unique<Stage>(system, mass_inverse, damping_over_mass, 2. / dt,
                                         linear_solver);
  }
  Stage &full = *start_full, &half = *start_half;
  dealii::Vector<double> rho_q(x0.q), rho_v(x0.v);
  rho_q *= 1. / dt;
  rho_v *= 1. / dt;
  form_history(full.c, rho_q, rho_v);
  const DynamicState coarse = implicit_step(full, rho_q, rho_v, x0.t + dt, x0.active);
  const std::vector<unsigned int> coarse_forces = active_set.force_indices();
  rho_q = x0.q;
  rho_v = x0.v;
  rho_q *= 2. / dt;
  rho_v *= 2. / dt;
  form_history(half.c, rho_q, rho_v);
  const DynamicState mid = implicit_step(half, rho_q, rho_v, x0.t + 0.5 * dt, x0.active);
  rho_q = mid.q;
  rho_v = mid.v;
  rho_q *= 2. / dt;
  rho_v *= 2. / dt;
  form_history(half.c, rho_q, rho_v);
  DynamicState fine = implicit_step(half, rho_q, rho_v, x0.t + dt, mid.active);
  // The impulses of both half steps.
  fine.impulse = combined_impulses(mid.impulse, 1., fine.impulse, 1.);
  // Extrapolated where both results solve the same equations: the same
  // constraints hold, the same of them carry a force (a touching one has
  // lambda = 0), and an impact falls in the dt step iff in the first half.
  if (fine.active == coarse.active && active_set.force_indices() == coarse_forces &&
      mid.impulse.empty() == coarse.impulse.empty())
  {
    DynamicState x = fine;
    x.q.sadd(2., -1., coarse.q);
    x.v.sadd(2., -1., coarse.v);
    x.a.sadd(2., -1., coarse.a);
    for (unsigned int i = 0; i < x.lambda.size(); ++i)
      x.lambda[i] = 2. * x.lambda[i] - coarse.lambda[i];
    clamp_compliant_forces(system, x.lambda);
    x.impulse = combined_impulses(fine.impulse, 2., coarse.impulse, -1.);
    if (satisfies_unilateral_constraints(x))
      fine = std::move(x);
  }
  // Else the start keeps the dt/2 result, which the active-set iteration of
  // its two steps made consistent (Sec. 5.3).
  previous = x0;
  current = std::move(fine);
}

bool Bdf2Integrator::satisfies_unilateral_constraints(const DynamicState& x)
{
  const std::vector<ConstraintState>& rows = at_next.at(x.t);
  for (unsigned int i = 0; i < system.n_constraints(); ++i)
    if (system.constraints[i]->is_rigid_unilateral() &&
        (x.active[i] ? x.lambda[i] < 0. : rows[i].position_residual(x.q) < 0.))
      return false;
  return true;
}

void Bdf2Integrator::advance()
{
  if (step_number == 0 || restart)
    richardson_start();
  else
  {
    if (!bdf2)
    {
      bdf2 = std::make_unique<Stage>(system, mass_inverse, damping_over_mass, 1.5 / dt,
                                     linear_solver);
      bdf2->split_damping();
    }
    // rho = (4 x_n - x_{n-1}) / (2 dt) and the history h' = rho_v + (c + mu)
    // rho_q of the damping split (PatternOperators), in one pass per block,
    // unless the last step's final pass formed them (NextHistory)
    const unsigned int n = system.n_dofs();
    const std::vector<PatternOperators::Shift>& blocks = bdf2->split_operators->shifts();
    if (!history_ready)
    {
      step_rho_q.reinit(n, true);
      step_rho_v.reinit(n, true);
      history.reinit(n, true);
      for (const PatternOperators::Shift& b : blocks)
        bdf2_history(b.last - b.first, 2. / dt, -0.5 / dt, bdf2->c + b.mu,
                     current.q.begin() + b.first, previous.q.begin() + b.first,
                     current.v.begin() + b.first, previous.v.begin() + b.first,
                     step_rho_q.begin() + b.first, step_rho_v.begin() + b.first,
                     history.begin() + b.first);
    }
    for (auto* y : {&next_rho_q, &next_rho_v, &next_h})
      y->reinit(n, true);
    NextHistory request{
        current.q.begin(),  current.v.begin(), 2. / dt, -0.5 / dt, next_rho_q.begin(),
        next_rho_v.begin(), next_h.begin(),    &blocks, bdf2->c};
    next_history = &request;
    // x_{n-1} made by the start (the initial state, or the state after an
    // impact) may hold its constraints less tightly than a step does (the
    // static solution to about 1e-13 m): no constraint is settled then.
    const bool history_from_steps = step_number > 1 && previous.impulse.empty();
    DynamicState next =
        implicit_step(*bdf2, step_rho_q, step_rho_v, current.t + dt, current.active,
                      history_from_steps ? &previous.active : nullptr, std::move(spare));
    next_history = nullptr;
    spare = std::move(previous);
    previous = std::move(current);
    current = std::move(next);
    step_rho_q.swap(next_rho_q);
    step_rho_v.swap(next_rho_v);
    history.swap(next_h);
    history_ready = true;
  }
  // After an impact the BDF-2 history (x_n, x_{n-1}) spans the jump of the
  // velocities: start afresh from the state after it (Sec. 5.2's start).
  restart = !current.impulse.empty();
  history_ready = history_ready && !restart;
  ++step_number;
  ++stats.steps;
}

void Bdf2Integrator::save(CheckpointOut& archive) const
{
  archive << step_number << previous << current << restart;
  save_statistics(archive);
}

void Bdf2Integrator::load(CheckpointIn& archive)
{
  archive >> step_number >> previous >> current >> restart;
  history_ready = false;
  load_statistics(archive);
  check_loaded(previous, "x_{n-1}");
  check_loaded(current, "x_n");
  check_loaded_steps(step_number);
}

IntegratorEntry Bdf2Integrator::registry_entry()
{
  IntegratorEntry e;
  e.name = "bdf2";
  e.description =
      "two-step BDF on the stabilised index-2 formulation (38) with a Richardson start";
  e.explicit_step_limit = false;
  e.writes_checkpoints = true;
  e.locates_events = false;
  e.create = [](const SemiDiscreteSystem& system, const TimeIntegrationParameters& p)
  {
    return std::make_unique<Bdf2Integrator>(system, p.time_step,
                                            p.max_active_set_iterations, p.linear_solver);
  };
  return e;
}
} // namespace pantocat
