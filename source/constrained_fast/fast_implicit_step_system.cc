#include <pantocat/base/input_error.h>
#include <pantocat/constrained_fast/fast_implicit_step_system.h>
#include <pantocat/constrained_fast/iteration_matrix.h>
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
struct FastImplicitStepSystem::Stage : IterationMatrix
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

namespace
{
using Slot = FastImplicitStepSystem::Slot;
constexpr unsigned int force_law = 3; ///< the equation of an engaged spring
using Role = ImplicitStepSystem::Role;

/// d/k of a compliant constraint's law (0 for a rigid one).
double ratio_of(const Constraint& constraint)
{
  return constraint.is_compliant()
             ? constraint.compliance().damping / constraint.compliance().stiffness
             : 0.;
}

} // namespace

/// The vectors of solve_trial(), kept from step to step
/// so that a step allocates nothing once their sizes are reached.
struct FastImplicitStepSystem::TrialWorkspace
{
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

namespace
{
/// h = rho_v + kappa rho_q on @p n entries (compiled for AVX2 beside the
/// baseline; no fused multiply-add, so the same bits either way).
__attribute__((target_clones("avx2", "default"))) void
form_history(const unsigned int n, const double kappa, const double* __restrict rho_q,
             const double* __restrict rho_v, double* __restrict h)
{
  for (unsigned int i = 0; i < n; ++i)
    h[i] = rho_v[i] + kappa * rho_q[i];
}
} // namespace

FastImplicitStepSystem::FastImplicitStepSystem(const SemiDiscreteSystem& system,
                                               const double c,
                                               const LinearSolverType solver,
                                               const bool forms_next_history)
    : ImplicitStepSystem(system, c), damping_over_mass(system), operators(system),
      work(std::make_unique<TrialWorkspace>()),
      split(forms_next_history), whole_rows{{0, system.n_dofs(), 0., 0.}}
{
  mass_inverse.initialize(system.mass, system.mass_is_diagonal, "mass matrix M", solver);
  stage = std::make_unique<Stage>(system, mass_inverse, damping_over_mass, c, solver);
  if (split)
    stage->split_damping();
}

FastImplicitStepSystem::~FastImplicitStepSystem() = default;

void FastImplicitStepSystem::start(const std::vector<ConstraintState>& r, const double t,
                                   const dealii::Vector<double>& rq,
                                   const dealii::Vector<double>& rv,
                                   const std::vector<bool>* held, const NextHistory* next,
                                   const bool continued)
{
  const unsigned int n = system.n_dofs();
  keep_step(r, t, rq, rv, next);
  if (with_next)
  {
    for (auto* y : {&next_rho_q, &next_rho_v, &next_h})
      y->reinit(n, true);
  }
  Stage& s = *stage;
  if (!s.block_ready)
    s.initialize_block(r);
  // h = rho_v + c rho_q (+ mu rho_q per block of the damping split), unless
  // the last solve formed it with the history handed out.
  if (!continued || !history_ready)
  {
    history.reinit(n, true);
    if (split)
      for (const PatternOperators::Shift& b : s.split_operators->shifts())
        form_history(b.last - b.first, c + b.mu, rq.begin() + b.first,
                     rv.begin() + b.first, history.begin() + b.first);
    else
      form_history(n, c, rq.begin(), rv.begin(), history.begin());
  }
  history_ready = false;
  (s.split_operators ? *s.split_operators : operators).set_time(t);
  solve_base();
  // The moving constraints' columns on the rows they reach.
  for (unsigned int k = 0; k < s.moving.size(); ++k)
    s.compute_columns(s.S_columns[k], s.M_columns[k], r[s.moving[k]]);
  s.touching_columns.clear();
  base_levels_of_rows(held);
}

void FastImplicitStepSystem::solve_base()
{
  Stage& s = *stage;
  // S^-1 (f + M history + D rho_q), with the damping split if any
  (s.split_operators ? *s.split_operators : operators)
      .solve_history(history, *rho_q, s.inverse, s.base);
  base_taken = false;
}

void FastImplicitStepSystem::base_levels_of_rows(const std::vector<bool>* held)
{
  const unsigned int m_all = system.n_constraints();
  const std::vector<ConstraintState>& r = *rows;
  std::vector<bool>& settled = work->settled_at_start;
  settled.resize(m_all);
  for (unsigned int k = 0; k < m_all; ++k)
    settled[k] = settling && held && (*held)[k];
  // Of a constant row that may be settled, g alone (the block reads no more
  // of a settled one; solve_trial() completes them where a solve needs them).
  base_levels.resize(m_all);
  levels_complete.resize(m_all);
  for (unsigned int k = 0; k < m_all; ++k)
  {
    // (a constant row's G_t, G_tt are empty: their products are +0)
    const bool moves = r[k].G_t.size() > 0 || r[k].G_tt.size() > 0;
    levels_complete[k] = moves || !settled[k];
    if (levels_complete[k])
      base_levels[k] = complete_levels(r[k], c, stage->base, *rho_q, *rho_v);
    else
      base_levels[k] = {{r[k].G.dot(stage->base) + r[k].z, 0., 0.}};
  }
}

void FastImplicitStepSystem::solve(const std::vector<Role>& roles,
                                   dealii::Vector<double>& q, dealii::Vector<double>& v,
                                   dealii::Vector<double>& a, std::vector<double>& forces)
{
  // a solve takes the base's vector for q: solved again, the same bits
  if (base_taken)
    solve_base();
  ++solve_count;
  solve_trial(roles, q, v, a, forces);
  base_taken = true;
}

void FastImplicitStepSystem::take_next_history(dealii::Vector<double>& rq,
                                               dealii::Vector<double>& rv)
{
  rq.swap(next_rho_q);
  rv.swap(next_rho_v);
  history.swap(next_h);
  history_ready = true;
}

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

void FastImplicitStepSystem::solve_trial(const std::vector<Role>& roles,
                                         dealii::Vector<double>& q,
                                         dealii::Vector<double>& v,
                                         dealii::Vector<double>& a,
                                         std::vector<double>& forces)
{
  classify(roles);
  select_block(roles);
  block_right_hand_side();
  border_columns();
  border_rows();
  solve_bordered_system();
  multipliers(forces);
  form_solution(q, v, a);
}

void FastImplicitStepSystem::classify(const std::vector<Role>& role)
{
  Stage& s = *stage;
  const unsigned int n = system.n_dofs(), mF = s.fixed.size();
  // Fixed constraints with force or engaged form the block, the moving ones
  // and the touching fixed ones border it.
  TrialWorkspace& w = *work;
  w.force.assign(mF, false);
  w.engaged.assign(mF, false);
  w.unknowns.clear();
  w.equations.clear();
  w.border.clear();
  for (unsigned int i = 0; i < role.size(); ++i)
  {
    if (role[i] == Role::none)
      continue;
    const bool moving = s.moves[i];
    if (!moving && role[i] != Role::touching)
    {
      (role[i] == Role::force ? w.force : w.engaged)[s.position[i]] = true;
      continue;
    }
    w.border.push_back(i);
    if (role[i] == Role::force)
      w.unknowns.insert(w.unknowns.end(), {{i, lambda}, {i, eta}, {i, mu}}),
          w.equations.insert(w.equations.end(), {{i, 2}, {i, 0}, {i, 1}});
    else if (role[i] == Role::touching)
      w.unknowns.insert(w.unknowns.end(), {{i, eta}, {i, mu}}),
          w.equations.insert(w.equations.end(), {{i, 0}, {i, 1}});
    else
      w.unknowns.push_back({i, lambda}), w.equations.push_back({i, force_law});
    if (!moving && !s.touching_columns.count(i))
    {
      auto& [X, U] = s.touching_columns[i];
      X.reinit(n);
      U.reinit(n);
      s.compute_columns(X, U, (*rows)[i]);
    }
  }
}

void FastImplicitStepSystem::select_block(const std::vector<Role>& role)
{
  Stage& s = *stage;
  TrialWorkspace& w = *work;
  const unsigned int mF = s.fixed.size();
  // The fixed rows in the block that each border constraint's columns reach.
  w.near.resize(w.border.size());
  w.in_block.resize(mF);
  for (unsigned int k = 0; k < mF; ++k)
    w.in_block[k] = w.force[k] || w.engaged[k];
  w.near_slot.assign(mF, -1);
  for (std::size_t b = 0; b < w.border.size(); ++b)
    s.reached_fixed_rows(w.border[b], w.in_block, w.near[b], w.near_slot);
  // Settled: held at the history points and out of the reach of the border's
  // mass columns, whose mu and eta (moving contacts, touching constraints)
  // would otherwise change its levels 1 and 2 (GglFixedBlock::select()).
  w.settled.assign(mF, false);
  for (unsigned int k = 0; k < mF; ++k)
    w.settled[k] = w.force[k] && w.settled_at_start[s.fixed[k]];
  for (std::size_t b = 0; b < w.border.size(); ++b)
    if (role[w.border[b]] != Role::engaged)
      for (const Reached& f : w.near[b])
        w.settled[f.k] = w.settled[f.k] && !f.by_mass_columns;
  s.block.select(w.force, w.engaged, w.settled);
  settled_count = s.block.n_settled();
}

FastImplicitStepSystem::Levels FastImplicitStepSystem::border_levels(const unsigned int k,
                                                                     const Slot& u) const
{
  const auto [X, U] = stage->batches(u.constraint);
  const ConstraintState& r = (*rows)[k];
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
}

double FastImplicitStepSystem::value(const Levels& L, const Slot& e) const
{
  return e.kind == force_law ? L[0] + ratio_of(*system.constraints[e.constraint]) * L[1]
                             : L[e.kind];
}

void FastImplicitStepSystem::fixed_slots(const unsigned int k, const Levels& L,
                                         dealii::Vector<double>& v) const
{
  if (work->force[k])
  {
    v[3 * k + 1] = L[0];
    v[3 * k + 2] = L[1] - c * L[0];
    v[3 * k] = L[2] - c * L[1];
  }
  else if (work->engaged[k])
    v[3 * k] = L[0] + stage->block.damping_ratio(k) * L[1];
}

const FastImplicitStepSystem::Levels&
FastImplicitStepSystem::levels_of(const unsigned int i)
{
  if (!levels_complete[i])
  {
    base_levels[i] = complete_levels((*rows)[i], c, stage->base, *rho_q, *rho_v);
    levels_complete[i] = true;
  }
  return base_levels[i];
}

void FastImplicitStepSystem::block_right_hand_side()
{
  const Stage& s = *stage;
  TrialWorkspace& w = *work;
  const unsigned int mF = s.fixed.size();
  w.r.reinit(3 * mF);
  w.y.reinit(w.unknowns.size());
  for (unsigned int k = 0; k < mF; ++k)
  {
    if (w.force[k] && !s.block.has_eta_mu(k)) // settled: the block reads g alone
      w.r[3 * k + 1] = -base_levels[s.fixed[k]][0];
    else if (w.force[k] || w.engaged[k])
    {
      const Levels& g = levels_of(s.fixed[k]);
      fixed_slots(k, {{-g[0], -g[1], -g[2]}}, w.r);
    }
  }
}

void FastImplicitStepSystem::border_columns()
{
  const Stage& s = *stage;
  TrialWorkspace& w = *work;
  const unsigned int p = w.unknowns.size(), mF = s.fixed.size();
  // Bc and Cr are zero between solves (set back on the slots they used).
  w.Bc.resize(p);
  w.Cr.resize(p);
  for (unsigned int u = 0; u < p; ++u)
    for (dealii::Vector<double>* v : {&w.Bc[u], &w.Cr[u]})
      if (v->size() != 3 * mF)
        v->reinit(3 * mF);
  w.D.reinit(p, p);
  // Fixed rows against the border columns: G_t = G_tt = 0 on them, and the
  // unknowns of one border constraint share its batches, so each fixed row
  // takes its products with them once (the values border_levels() gives).
  using Products = std::array<double, InterleavedColumns::width>;
  for (unsigned int u0 = 0, u1 = 0, b = 0; u0 < p; u0 = u1, ++b)
  {
    while (u1 < p && w.unknowns[u1].constraint == w.unknowns[u0].constraint)
      ++u1;
    const auto [X, U] = s.batches(w.unknowns[u0].constraint);
    // Rows the columns do not reach keep their zeros (their products are +0).
    for (const Reached& f : w.near[b])
    {
      const SparseRow& G = (*rows)[s.fixed[f.k]].G;
      const Products GX = f.by_columns ? X->dots(G) : Products{},
                     GU = f.by_mass_columns ? U->dots(G) : Products{};
      for (unsigned int u = u0; u < u1; ++u)
      {
        const unsigned int kind = w.unknowns[u].kind;
        fixed_slots(f.k,
                    functionals(c, GX[kind], 0., 0.,
                                kind == eta  ? GU[Z]
                                : kind == mu ? GU[Y]
                                             : 0.,
                                0., kind == eta ? GU[Y] : 0.),
                    w.Bc[u]);
      }
    }
  }
}

void FastImplicitStepSystem::border_rows()
{
  TrialWorkspace& w = *work;
  // The fixed rows that a border column reaches: the sources of the local
  // solve (GglFixedBlock::local_subset()); border_row() adds those that
  // reach a border row.
  w.sources.clear();
  for (std::size_t b = 0; b < w.border.size(); ++b)
    for (const Reached& f : w.near[b])
      w.sources.push_back(f.k);
  unsigned int products_of = system.n_constraints();
  for (unsigned int e = 0; e < w.unknowns.size(); ++e)
  {
    if (products_of != w.equations[e].constraint)
    {
      products_of = w.equations[e].constraint;
      fixed_columns_on_row((*rows)[products_of]);
    }
    border_row(e);
  }
}

void FastImplicitStepSystem::fixed_columns_on_row(const ConstraintState& row)
{
  TrialWorkspace& w = *work;
  const GglFixedBlock& block = stage->block;
  const TruncatedColumns& X = block.stiffness_columns();
  X.row_products(row.G, w.X0);
  X.row_products(row.G_t, w.X1);
  X.row_products(row.G_tt, w.X2);
  X.partner_row_products(row.G, w.V0);
  X.partner_row_products(row.G_t, w.V1);
  X.partner_row_products(row.G_tt, w.V2);
  block.mass_columns().row_products(row.G, w.Y0);
  block.mass_columns().row_products(row.G_t, w.Y1);
  // The fixed columns that reach this row (the others' entries stay 0).
  w.reached_by_row.clear();
  for (unsigned int l = 0; l < stage->fixed.size(); ++l)
    if ((w.force[l] || w.engaged[l]) &&
        (w.X0[l] != 0. || w.X1[l] != 0. || w.X2[l] != 0. || w.V0[l] != 0. ||
         w.V1[l] != 0. || w.V2[l] != 0. || w.Y0[l] != 0. || w.Y1[l] != 0.))
      w.reached_by_row.push_back(l);
  w.sources.insert(w.sources.end(), w.reached_by_row.begin(), w.reached_by_row.end());
}

void FastImplicitStepSystem::border_row(const unsigned int e)
{
  TrialWorkspace& w = *work;
  const GglFixedBlock& block = stage->block;
  const Slot& eq = w.equations[e];
  // Border row against the fixed unknowns, from the truncated columns.
  for (const unsigned int l : w.reached_by_row)
  {
    w.Cr[e][3 * l] = value(functionals(c, w.X0[l], w.X1[l], w.X2[l], 0., 0., 0.), eq);
    if (!w.force[l] || !block.has_eta_mu(l)) // a settled one's eta, mu are 0
      continue;
    w.Cr[e][3 * l + 1] =
        value(functionals(c, w.X0[l], w.X1[l], w.X2[l], 0., 0., w.Y0[l]), eq);
    w.Cr[e][3 * l + 2] =
        value(functionals(c, w.V0[l], w.V1[l], w.V2[l], w.Y0[l], w.Y1[l], 0.), eq);
  }
  // Against the border unknowns.
  for (unsigned int u = 0; u < w.unknowns.size(); ++u)
  {
    w.D(e, u) = value(border_levels(eq.constraint, w.unknowns[u]), eq);
    if (eq.kind == force_law && w.unknowns[u].constraint == eq.constraint)
      w.D(e, u) += 1. / system.constraints[eq.constraint]->compliance().stiffness;
  }
  w.y(e) = -value(levels_of(eq.constraint), eq);
}

void FastImplicitStepSystem::solve_bordered_system()
{
  TrialWorkspace& w = *work;
  GglFixedBlock& block = stage->block;
  const unsigned int p = w.unknowns.size();
  std::sort(w.sources.begin(), w.sources.end());
  w.sources.erase(std::unique(w.sources.begin(), w.sources.end()), w.sources.end());
  local_size = 0;
  if (p > 0 && stage->fixed.size() > 0 && border_locally && block.local_subset(w.sources))
  {
    solve_bordered_locally(block, w.Bc, w.Cr, w.D, w.r, w.y, w.rhs, w.batch, time);
    local_size = block.local_members().size();
    return;
  }
  solve_bordered([&](const auto& xs) { block.solve(xs); }, w.Bc, w.Cr, w.D, w.r, w.y,
                 w.rhs, w.batch, time, "BDF step");
  for (unsigned int u = 0; u < p; ++u)
  {
    w.Bc[u] = 0.;
    w.Cr[u] = 0.;
  }
}

void FastImplicitStepSystem::multipliers(std::vector<double>& forces)
{
  TrialWorkspace& w = *work;
  const unsigned int mF = stage->fixed.size();
  forces.assign(system.n_constraints(), 0.);
  w.lambda_eta.resize(mF);
  w.eta_F.resize(mF);
  w.mu_F.resize(mF);
  for (unsigned int k = 0; k < mF; ++k)
  {
    forces[stage->fixed[k]] = w.r[3 * k];
    w.lambda_eta[k] = w.r[3 * k] + w.r[3 * k + 1];
    w.eta_F[k] = w.r[3 * k + 1];
    w.mu_F[k] = w.r[3 * k + 2];
  }
  for (unsigned int u = 0; u < w.unknowns.size(); ++u)
    if (w.unknowns[u].kind == lambda)
      forces[w.unknowns[u].constraint] = w.y(u);
}

void FastImplicitStepSystem::form_solution(dealii::Vector<double>& q,
                                           dealii::Vector<double>& v,
                                           dealii::Vector<double>& a)
{
  //   q = base + sum_l lambda_l X^lambda_l + eta_l X^eta_l + mu_l X^mu_l,
  //   v = c q - rho_q - sum_l (mu_l Y_l + eta_l Z_l),  a = c v - rho_v - sum_l eta_l Y_l
  // (fixed: X^eta = X^lambda, Z = 0). q takes the base's vector (no copy;
  // solve() solves for the base again before another solve). q, v, a are
  // formed from the base and the fixed forces' sums in combine_trial()'s
  // pass (no zeroing), unless add_forces() adds them first: by solves (many
  // constraints close together on a FEM grid) or when their sums reach many
  // short stretches of rows.
  Stage& s = *stage;
  TrialWorkspace& w = *work;
  const unsigned int n = system.n_dofs(), mF = s.fixed.size();
  const bool forces_added_first = mF > 0 && !s.block.sums_in_one_pass();
  GglFixedBlock::ForceSums sums;
  q.swap(s.base);
  if (forces_added_first)
  {
    v.reinit(n);
    a.reinit(n);
    s.block.add_forces(w.lambda_eta, w.eta_F, w.mu_F, q, v, a); // v, a: u1, u2
  }
  else
  {
    v.reinit(n, true);
    a.reinit(n, true);
    if (mF > 0)
      sums = s.block.sum_forces(w.lambda_eta, w.eta_F, w.mu_F);
  }
  border_terms_of_solution();
  HistoryPass pass{};
  if (with_next)
    pass = {next_request.q_n->begin(),
            next_request.v_n->begin(),
            next_request.f,
            next_request.fp,
            next_rho_q.begin(),
            next_rho_v.begin(),
            next_h.begin(),
            split ? &s.split_operators->shifts() : &whole_rows,
            c};
  combine_trial(border_terms, w.reach, c, *rho_q, *rho_v, !forces_added_first,
                mF > 0 && !forces_added_first ? &sums : nullptr,
                with_next ? &pass : nullptr, q, v, a);
}

void FastImplicitStepSystem::border_terms_of_solution()
{
  // The border columns, then v and a, in one pass; on each unknown the
  // border unknowns add in their order.
  TrialWorkspace& w = *work;
  border_terms.clear();
  w.reach.clear();
  for (unsigned int u = 0; u < w.unknowns.size(); ++u)
  {
    const auto [X, U] = stage->batches(w.unknowns[u].constraint);
    if (u == 0 || w.unknowns[u].constraint != w.unknowns[u - 1].constraint)
    {
      add_ranges(w.reach, X->reach(), w.reach_scratch);
      add_ranges(w.reach, U->reach(), w.reach_scratch);
    }
    const unsigned int kind = w.unknowns[u].kind;
    const double f = w.y(u);
    border_terms.push_back({X->data() + kind, U->data(), f, kind == mu ? f : 0.,
                            kind == eta ? f : 0., kind == eta ? f : 0.});
  }
}
namespace
{
/**
 * The next step's history on a block's rows, formed in the step's last pass
 * from the q_{n+1}, v_{n+1} it has just stored: rho_q' = f q_{n+1} + fp q_n,
 * rho_v' = f v_{n+1} + fp v_n, h' = rho_v' + kappa rho_q' (kappa = c + mu of
 * the block), each entry as start() forms h from them at the next step.
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
void by_blocks(const FastImplicitStepSystem::HistoryPass* next, const RowRange rows,
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
 * q, v, a += P border terms (FastImplicitStepSystem::BorderTerm) in one pass; in the
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

void FastImplicitStepSystem::combine_trial(
    const std::vector<BorderTerm>& terms, const RowRanges& reach, const double c,
    const dealii::Vector<double>& rho_q, const dealii::Vector<double>& rho_v,
    const bool from_base, const GglFixedBlock::ForceSums* sums, const HistoryPass* next,
    dealii::Vector<double>& q_out, dealii::Vector<double>& v_out,
    dealii::Vector<double>& a_out)
{
  const int n = q_out.size();
  double *q = q_out.begin(), *v = v_out.begin(), *a = a_out.begin();
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
} // namespace pantocat
