// A speed-of-light kernel for FDM + half-explicit (39)-(41) on the paper's
// benchmark structure (issue 16): one fused sweep over both wires per step,
// reading q, v, v_prev and writing q_new, v_new, with every piece of
// constraint work local (the contact row and the small multiplier systems on
// the few nodes that the contact and the droppers touch). Only for the
// benchmarks in bench/: it is a second implementation of the same method,
// checked against the library's contact force by bench_integrators.
#pragma once

#include <pantocat/space/smoothed_delta.h>
#include <pantocat/system/semi_discrete_system.h>
#include <pantocat/time/dynamic_state.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace pantocat::bench
{
/// The contact's motion and its smoothed delta: x_p(t) = x0 + speed t.
struct FusedContact
{
  double initial_position = 2.;
  double speed = 32.;
  double half_width = 0.2;    ///< epsilon of the smoothed delta
  double grid_spacing = 0.04; ///< dx of the FDM grid [m]
};

/**
 * FDM + half-explicit for two wires (a string: tridiagonal K, and a beam:
 * pentadiagonal K with the simply supported ends of (3)), diagonal M and D,
 * a two-coordinate pantograph whose first coordinate touches the contact
 * wire, rigid point droppers between the wires, and the moving smoothed
 * contact. The coefficients are read from a SemiDiscreteSystem of that
 * structure and checked to be uniform (the constructor throws otherwise); the
 * time loop uses them as scalars.
 *
 * A step is: (1) the contact rows at t_n, t_{n+1/2}, t_{n+1} and the
 * acceleration a_n at the constrained nodes, the multipliers lambda_n of
 * g^(II) = 0 (a small dense system of the contact and the droppers under its
 * support; every other dropper alone); (2) one sweep over the nodes of both
 * wires computing a_n without constraint forces, v* = v_{n-1} + 2 dt a_n and
 * q* = q_n + dt (v_n + v*)/2; (3) the constraint forces' corrections at the
 * constrained nodes; (4) eta, mu of (40) from g = dg/dt = 0 at t_{n+1}, again
 * locally, and their corrections. All constraints are taken active
 * (bilateral): the 32 m/s benchmark keeps every dropper and the contact
 * closed.
 */
class FusedHalfExplicit
{
public:
  FusedHalfExplicit(const SemiDiscreteSystem& system, const DynamicState& initial,
                    const FusedContact& contact, unsigned int contact_index,
                    const std::vector<unsigned int>& dropper_indices, double time_step)
      : dt(time_step), delta(contact.half_width), contact(contact)
  {
    read_blocks(system);
    read_wire_coefficients(system);
    read_pantograph(system);
    read_constraints(system, contact_index, dropper_indices);
    set_state(initial);
    const std::size_t support = 2 * static_cast<std::size_t>(std::ceil(
                                        contact.half_width / contact.grid_spacing)) +
                                4;
    for (Row* r : {&at_n, &at_half, &at_next})
      for (auto* x : {&r->g, &r->g_t, &r->g_tt})
        x->assign(support, 0.);
  }

  /// One step t_n -> t_{n+1}; contact_force() is then lambda_n of the contact.
  void step()
  {
    contact_rows();
    acceleration_multipliers();
    sweep();
    add_acceleration_corrections();
    project();
    std::swap(q, q_new);
    std::swap(v_prev, v);
    std::swap(v, v_new); // v_new now holds v_{n-1}'s buffer: overwritten next step
    t += dt;
  }

  double contact_force() const { return lambda_contact; }
  double time() const { return t; }

private:
  /// A wire's state vector with two zero ghost nodes on each side.
  struct Wires
  {
    std::vector<double> c, w; ///< carrier, contact wire (size N + 4)
    double p[2] = {0., 0.};   ///< pantograph (contact coordinate first)
    double* carrier() { return c.data() + 2; }
    double* wire() { return w.data() + 2; }
  };
  /// A contact row over the wire nodes first..first+size-1 (0-based).
  struct Row
  {
    int first = 0, size = 0;
    std::vector<double> g, g_t, g_tt;
    double at(const std::vector<double>& x, const int node) const
    {
      const int k = node - first;
      return k >= 0 && k < size ? x[k] : 0.;
    }
  };
  /// A point load at a node: f = f_uniform + extra there.
  struct PointLoad
  {
    int node = 0;
    double carrier = 0., wire = 0.;
  };
  /// A rigid point dropper: q_w[node] - q_c[node] + z = 0.
  struct Dropper
  {
    int node = 0;
    double z = 0., lambda = 0.;
  };

  static double coefficient(const dealii::SparseMatrix<double>& A, unsigned int i,
                            unsigned int j)
  {
    return A.el(i, j);
  }

  void read_blocks(const SemiDiscreteSystem& s)
  {
    const DofBlock& c = s.block("carrier");
    const DofBlock& w = s.block("contact wire");
    if (c.size != w.size || s.blocks.size() != 3 || s.blocks[2].size != 2)
      throw std::runtime_error("fused kernel: needs carrier, contact wire (same grid) "
                               "and a two-coordinate pantograph");
    N = c.size;
    oc = c.first;
    ow = w.first;
    op = s.blocks[2].first;
  }

  /// Checks that @p value equals @p expected to 1e-12 relative, else throws.
  static void require_uniform(const double value, const double expected, const char* what)
  {
    if (std::abs(value - expected) > 1e-12 * std::max(1., std::abs(expected)))
      throw std::runtime_error(std::string("fused kernel: non-uniform ") + what);
  }

  void read_wire_coefficients(const SemiDiscreteSystem& s)
  {
    kc0 = coefficient(s.stiffness, oc + 1, oc + 1);
    kc1 = coefficient(s.stiffness, oc + 1, oc + 2);
    kw0 = coefficient(s.stiffness, ow + 2, ow + 2);
    kw0_end = coefficient(s.stiffness, ow, ow);
    kw1 = coefficient(s.stiffness, ow + 2, ow + 3);
    kw2 = coefficient(s.stiffness, ow + 2, ow + 4);
    const double mc = s.mass.diag_element(oc), mw = s.mass.diag_element(ow);
    const double dc = s.damping.diag_element(oc), dw = s.damping.diag_element(ow);
    fc = s.load(oc);
    fw = s.load(ow);
    // Point loads (clamp and dropper masses, Eq. (4)) are exceptions of f.
    extra_fc.assign(N + 4, 0.);
    extra_fw.assign(N + 4, 0.);
    for (int i = 0; i < N; ++i)
    {
      if (s.load(oc + i) != fc)
        point_loads.push_back({i, s.load(oc + i) - fc, s.load(ow + i) - fw});
      else if (s.load(ow + i) != fw)
        point_loads.push_back({i, 0., s.load(ow + i) - fw});
      extra_fc[i + 2] = s.load(oc + i) - fc;
      extra_fw[i + 2] = s.load(ow + i) - fw;
    }
    for (int i = 0; i < N; ++i)
    {
      require_uniform(coefficient(s.stiffness, oc + i, oc + i), kc0, "carrier K");
      if (i + 1 < N)
        require_uniform(coefficient(s.stiffness, oc + i, oc + i + 1), kc1, "carrier K");
      const bool end = i == 0 || i == N - 1;
      require_uniform(coefficient(s.stiffness, ow + i, ow + i), end ? kw0_end : kw0,
                      "wire K");
      if (i + 1 < N)
        require_uniform(coefficient(s.stiffness, ow + i, ow + i + 1), kw1, "wire K");
      if (i + 2 < N)
        require_uniform(coefficient(s.stiffness, ow + i, ow + i + 2), kw2, "wire K");
      require_uniform(s.mass.diag_element(oc + i), mc, "carrier M");
      require_uniform(s.mass.diag_element(ow + i), mw, "wire M");
      require_uniform(s.damping.diag_element(oc + i), dc, "carrier D");
      require_uniform(s.damping.diag_element(ow + i), dw, "wire D");
    }
    half_dc = 0.5 * dc;
    half_dw = 0.5 * dw;
    ic = 1. / (mc + 0.5 * dt * dc);
    iw = 1. / (mw + 0.5 * dt * dw);
    jc = 1. / mc;
    jw = 1. / mw;
  }

  /// The inverse of a symmetric 2x2 matrix [a b; b d].
  static std::array<double, 4> inverse(const double a, const double b, const double d)
  {
    const double det = a * d - b * b;
    return {{d / det, -b / det, -b / det, a / det}};
  }

  void read_pantograph(const SemiDiscreteSystem& s)
  {
    for (int r = 0; r < 2; ++r)
    {
      fp[r] = s.load(op + r);
      for (int c = 0; c < 2; ++c)
      {
        kp[2 * r + c] = coefficient(s.stiffness, op + r, op + c);
        half_dp[2 * r + c] = 0.5 * coefficient(s.damping, op + r, op + c);
      }
    }
    const auto m = [&](int r, int c) { return coefficient(s.mass, op + r, op + c); };
    const auto d = [&](int r, int c) { return coefficient(s.damping, op + r, op + c); };
    wp = inverse(m(0, 0) + 0.5 * dt * d(0, 0), m(0, 1) + 0.5 * dt * d(0, 1),
                 m(1, 1) + 0.5 * dt * d(1, 1));
    mp = inverse(m(0, 0), m(0, 1), m(1, 1));
  }

  void read_constraints(const SemiDiscreteSystem& s, const unsigned int contact_index,
                        const std::vector<unsigned int>& dropper_indices)
  {
    ConstraintState state;
    s.constraints[contact_index]->evaluate(0., state, 0);
    bool head_found = false;
    for (std::size_t k = 0; k < state.G.size(); ++k)
      if (state.G.index[k] == op)
        head_found = state.G.value[k] == -1.;
    if (!head_found)
      throw std::runtime_error("fused kernel: the contact must hold the pantograph's "
                               "first coordinate with -1");
    for (const unsigned int i : dropper_indices)
    {
      s.constraints[i]->evaluate(0., state, 0);
      Dropper d;
      d.z = state.z;
      d.node = -1;
      for (std::size_t k = 0; k < state.G.size(); ++k)
        if (state.G.index[k] >= ow && state.G.index[k] < ow + N && state.G.value[k] == 1.)
          d.node = state.G.index[k] - ow;
      if (state.G.size() != 2 || d.node < 0 ||
          state.G.dot(unit(s.n_dofs(), oc + d.node)) != -1.)
        throw std::runtime_error("fused kernel: a dropper must be a point row "
                                 "q_w[i] - q_c[i] + z");
      droppers.push_back(d);
    }
  }

  static dealii::Vector<double> unit(const unsigned int n, const unsigned int i)
  {
    dealii::Vector<double> e(n);
    e(i) = 1.;
    return e;
  }

  void set_state(const DynamicState& initial)
  {
    for (Wires* x : {&q, &q_new, &v, &v_prev, &v_new})
    {
      x->c.assign(N + 4, 0.);
      x->w.assign(N + 4, 0.);
    }
    t = initial.t;
    for (int i = 0; i < N; ++i)
    {
      q.carrier()[i] = initial.q(oc + i);
      q.wire()[i] = initial.q(ow + i);
      v.carrier()[i] = initial.v(oc + i);
      v.wire()[i] = initial.v(ow + i);
      // v_{-1} = v_0 - dt a_0, as the library starts.
      v_prev.carrier()[i] = initial.v(oc + i) - dt * initial.a(oc + i);
      v_prev.wire()[i] = initial.v(ow + i) - dt * initial.a(ow + i);
    }
    for (int r = 0; r < 2; ++r)
    {
      q.p[r] = initial.q(op + r);
      v.p[r] = initial.v(op + r);
      v_prev.p[r] = initial.v(op + r) - dt * initial.a(op + r);
    }
  }

  /// The rows of the contact at @p time: G, and G_t, G_tt as asked.
  void contact_row(const double time, Row& r, const bool second) const
  {
    const double x = contact.initial_position + contact.speed * time, xd = contact.speed;
    const double dx = spacing(), eps = delta.epsilon();
    const int first = std::max(1, static_cast<int>(std::floor((x - eps) / dx + 0.5)));
    const int last = std::min(N, static_cast<int>(std::floor((x + eps) / dx + 0.5)));
    r.first = first - 1;
    r.size = last - first + 1;
    for (int i = first; i <= last; ++i)
    {
      const double lo = (i - 0.5) * dx - x, hi = (i + 0.5) * dx - x;
      const double dv = delta.value(hi) - delta.value(lo);
      r.g[i - first] = delta.integral_up_to(hi) - delta.integral_up_to(lo);
      r.g_t[i - first] = -xd * dv;
      if (second)
        r.g_tt[i - first] = xd * xd * (delta.derivative(hi, 1) - delta.derivative(lo, 1));
    }
  }

  double spacing() const { return contact.grid_spacing; }

  void contact_rows()
  {
    contact_row(t, at_n, true);
    contact_row(t + 0.5 * dt, at_half, false);
    contact_row(t + dt, at_next, false);
    window_first = std::min({at_n.first, at_half.first, at_next.first});
    window_last = std::max({at_n.first + at_n.size, at_half.first + at_half.size,
                            at_next.first + at_next.size}) -
                  1;
    near.clear();
    for (unsigned int j = 0; j < droppers.size(); ++j)
      if (droppers[j].node >= window_first && droppers[j].node <= window_last)
        near.push_back(j);
  }

  /// a without constraint forces at carrier node i (ghosts make it branch-free).
  double carrier_acceleration(const int i) const
  {
    const double* x = q.c.data() + 2;
    const double s = fc + extra_fc[i + 2] - kc0 * x[i] - kc1 * (x[i - 1] + x[i + 1]) -
                     half_dc * (v_prev.c[i + 2] + v.c[i + 2]);
    return s * ic;
  }
  /// a without constraint forces at wire node i, with diagonal @p k0.
  double wire_acceleration(const int i, const double k0) const
  {
    const double* x = q.w.data() + 2;
    const double s = fw + extra_fw[i + 2] - k0 * x[i] - kw1 * (x[i - 1] + x[i + 1]) -
                     kw2 * (x[i - 2] + x[i + 2]) -
                     half_dw * (v_prev.w[i + 2] + v.w[i + 2]);
    return s * iw;
  }
  double wire_acceleration(const int i) const
  {
    return wire_acceleration(i, i == 0 || i == N - 1 ? kw0_end : kw0);
  }
  /// The pantograph's a without the contact force: (M + dt/2 D)^-1 (f - K q - D v~).
  std::array<double, 2> pantograph_acceleration() const
  {
    double s[2];
    for (int r = 0; r < 2; ++r)
      s[r] = fp[r] - kp[2 * r] * q.p[0] - kp[2 * r + 1] * q.p[1] -
             half_dp[2 * r] * (v_prev.p[0] + v.p[0]) -
             half_dp[2 * r + 1] * (v_prev.p[1] + v.p[1]);
    return {{wp[0] * s[0] + wp[1] * s[1], wp[2] * s[0] + wp[3] * s[1]}};
  }

  /// Gaussian elimination with partial pivoting of the n x n system A x = b.
  static void solve_small(const int n, double* A, double* b)
  {
    for (int k = 0; k < n; ++k)
    {
      int p = k;
      for (int i = k + 1; i < n; ++i)
        if (std::abs(A[i * n + k]) > std::abs(A[p * n + k]))
          p = i;
      for (int j = 0; j < n; ++j)
        std::swap(A[k * n + j], A[p * n + j]);
      std::swap(b[k], b[p]);
      for (int i = k + 1; i < n; ++i)
      {
        const double f = A[i * n + k] / A[k * n + k];
        for (int j = k; j < n; ++j)
          A[i * n + j] -= f * A[k * n + j];
        b[i] -= f * b[k];
      }
    }
    for (int i = n - 1; i >= 0; --i)
    {
      for (int j = i + 1; j < n; ++j)
        b[i] -= A[i * n + j] * b[j];
      b[i] /= A[i * n + i];
    }
  }

  /**
   * lambda_n from g^(II) = G a + 2 G_t v + G_tt q = 0 with a = a0 + (M + dt/2
   * D)^-1 G^T lambda: the contact with the droppers under it in one small
   * system, the other droppers one by one.
   */
  void acceleration_multipliers()
  {
    const double* qw = q.w.data() + 2;
    const double* vw = v.w.data() + 2;
    double r_c = 0.;
    for (int k = 0; k < at_n.size; ++k)
    {
      const int i = at_n.first + k;
      r_c += at_n.g[k] * wire_acceleration(i) + 2. * at_n.g_t[k] * vw[i] +
             at_n.g_tt[k] * qw[i];
    }
    head_free = pantograph_acceleration();
    r_c -= head_free[0];
    const int p = 1 + static_cast<int>(near.size());
    double S[16 * 16] = {}, b[16] = {};
    if (p > 16)
      throw std::runtime_error("fused kernel: too many droppers under the contact");
    double gg = 0.;
    for (int k = 0; k < at_n.size; ++k)
      gg += at_n.g[k] * at_n.g[k] * iw;
    S[0] = gg + wp[0];
    b[0] = -r_c;
    for (int l = 0; l < p - 1; ++l)
    {
      const Dropper& d = droppers[near[l]];
      const double s_dc = at_n.at(at_n.g, d.node) * iw;
      S[l + 1] = S[(l + 1) * p] = s_dc;
      S[(l + 1) * p + l + 1] = iw + ic;
      b[l + 1] = -(wire_acceleration(d.node) - carrier_acceleration(d.node));
    }
    solve_small(p, S, b);
    lambda_contact = b[0];
    for (int l = 0; l < p - 1; ++l)
      droppers[near[l]].lambda = b[l + 1];
    std::size_t next = 0; // near is sorted
    for (unsigned int j = 0; j < droppers.size(); ++j)
    {
      if (next < near.size() && near[next] == j)
      {
        ++next;
        continue;
      }
      Dropper& d = droppers[j];
      d.lambda = -(wire_acceleration(d.node) - carrier_acceleration(d.node)) / (iw + ic);
    }
  }

  /// The uniform coefficients of the sweep, as local values (no aliasing with stores).
  struct SweepCoefficients
  {
    double fc, kc0, kc1, half_dc, ic, fw, kw0, kw1, kw2, half_dw, iw, h2, h_half;
  };

  /**
   * Nodes [first, last) of both wires: a0, v* = v_{n-1} + 2 dt a0, q* = q_n +
   * dt (v_n + v*)/2, with the wire's diagonal @p kw0 (the arrays have ghosts).
   * Compiled for AVX2 beside the baseline, as the library's sweep
   * (uniform_run_forces()): the speed of light of this machine, not of SSE2.
   */
  __attribute__((target_clones("avx2", "default"))) static void
  sweep_nodes(const int first, const int last, const SweepCoefficients k,
              const double kw0, const double* __restrict qc, const double* __restrict qw,
              const double* __restrict vc, const double* __restrict vw,
              const double* __restrict pc, const double* __restrict pw,
              double* __restrict nqc, double* __restrict nqw, double* __restrict nvc,
              double* __restrict nvw)
  {
    for (int i = first; i < last; ++i)
    {
      const double ac = (k.fc - k.kc0 * qc[i] - k.kc1 * (qc[i - 1] + qc[i + 1]) -
                         k.half_dc * (pc[i] + vc[i])) *
                        k.ic;
      const double aw = (k.fw - kw0 * qw[i] - k.kw1 * (qw[i - 1] + qw[i + 1]) -
                         k.kw2 * (qw[i - 2] + qw[i + 2]) - k.half_dw * (pw[i] + vw[i])) *
                        k.iw;
      const double vc1 = pc[i] + k.h2 * ac, vw1 = pw[i] + k.h2 * aw;
      nvc[i] = vc1;
      nvw[i] = vw1;
      nqc[i] = qc[i] + k.h_half * (vc[i] + vc1);
      nqw[i] = qw[i] + k.h_half * (vw[i] + vw1);
    }
  }

  /// The fused sweep over both wires, then the pantograph's two coordinates.
  void sweep()
  {
    const SweepCoefficients k{fc,  kc0, kc1,     half_dc, ic,      fw,      kw0,
                              kw1, kw2, half_dw, iw,      2. * dt, 0.5 * dt};
    const auto nodes = [&](const int first, const int last, const double k0)
    {
      sweep_nodes(first, last, k, k0, q.carrier(), q.wire(), v.carrier(), v.wire(),
                  v_prev.carrier(), v_prev.wire(), q_new.carrier(), q_new.wire(),
                  v_new.carrier(), v_new.wire());
    };
    nodes(0, 1, kw0_end);
    nodes(1, N - 1, kw0);
    nodes(N - 1, N, kw0_end);
    const double a[2] = {head_free[0] - lambda_contact * wp[0],
                         head_free[1] - lambda_contact * wp[2]};
    for (int r = 0; r < 2; ++r)
    {
      v_new.p[r] = v_prev.p[r] + k.h2 * a[r];
      q_new.p[r] = q.p[r] + k.h_half * (v.p[r] + v_new.p[r]);
    }
  }

  /**
   * v* += 2 dt y, q* += dt^2 y for y = (M + dt/2 D)^-1 (G^T lambda + the point
   * loads) on the wires: what the uniform sweep left out.
   */
  void add_acceleration_corrections()
  {
    double* nqc = q_new.c.data() + 2;
    double* nqw = q_new.w.data() + 2;
    double* nvc = v_new.c.data() + 2;
    double* nvw = v_new.w.data() + 2;
    const double h2 = 2. * dt, hh = dt * dt;
    for (const PointLoad& l : point_loads)
    {
      const double yc = l.carrier * ic, yw = l.wire * iw;
      nvc[l.node] += h2 * yc;
      nqc[l.node] += hh * yc;
      nvw[l.node] += h2 * yw;
      nqw[l.node] += hh * yw;
    }
    for (int k = 0; k < at_n.size; ++k)
    {
      const int i = at_n.first + k;
      const double y = lambda_contact * at_n.g[k] * iw;
      nvw[i] += h2 * y;
      nqw[i] += hh * y;
    }
    for (const Dropper& d : droppers)
    {
      const double yw = d.lambda * iw, yc = -d.lambda * ic;
      nvw[d.node] += h2 * yw;
      nqw[d.node] += hh * yw;
      nvc[d.node] += h2 * yc;
      nqc[d.node] += hh * yc;
    }
  }

  /**
   * eta, mu of (40) from g = dg/dt = 0 at t_{n+1}: q += M^-1 (h^2 G_n^T eta +
   * h G_t(t_{n+1/2})^T eta + h G(t_{n+1/2})^T mu), v += 2 h M^-1 G_n^T eta.
   */
  void project()
  {
    project_contact_and_near_droppers();
    project_other_droppers();
  }

  void project_contact_and_near_droppers()
  {
    double* nqc = q_new.c.data() + 2;
    double* nqw = q_new.w.data() + 2;
    double* nvc = v_new.c.data() + 2;
    double* nvw = v_new.w.data() + 2;
    const double h = dt;
    const int p = 1 + static_cast<int>(near.size()), n = 2 * p;
    // Unknowns (eta_0, .., eta_{p-1}, mu_0, .., mu_{p-1}), 0 the contact.
    double A[32 * 32] = {}, b[32] = {};
    // The contact's rows at t_{n+1}.
    double g = -q_new.p[0], gd = -v_new.p[0];
    for (int k = 0; k < at_next.size; ++k)
    {
      const int i = at_next.first + k;
      g += at_next.g[k] * nqw[i];
      gd += at_next.g_t[k] * nqw[i] + at_next.g[k] * nvw[i];
    }
    b[0] = -g;
    b[p] = -gd;
    // Contact row, contact column: G1 M^-1 G_n^T etc. (the head: M_p^-1).
    double GP = mp[0], GQ = 0., GR = mp[0], GtP = 0., GtQ = 0., GtR = 0.;
    for (int i = window_first; i <= window_last; ++i)
    {
      const double g1 = at_next.at(at_next.g, i), g1t = at_next.at(at_next.g_t, i);
      const double P = at_n.at(at_n.g, i) * jw, Q = at_half.at(at_half.g_t, i) * jw,
                   R = at_half.at(at_half.g, i) * jw;
      GP += g1 * P, GQ += g1 * Q, GR += g1 * R;
      GtP += g1t * P, GtQ += g1t * Q, GtR += g1t * R;
    }
    A[0] = h * h * GP + h * GQ;
    A[p] = h * GR;
    A[p * n] = h * h * GtP + h * GtQ + 2. * h * GP;
    A[p * n + p] = h * GtR;
    const double S = jw + jc;
    for (int l = 1; l < p; ++l)
    {
      const Dropper& d = droppers[near[l - 1]];
      const int i = d.node;
      b[l] = -(nqw[i] - nqc[i] + d.z);
      b[p + l] = -(nvw[i] - nvc[i]);
      // Dropper rows, dropper columns: [h^2 S, h S; 2h S, 0].
      A[l * n + l] = h * h * S;
      A[l * n + p + l] = h * S;
      A[(p + l) * n + l] = 2. * h * S;
      // Dropper rows, contact columns (G_d M^-1 G_c^T at node i).
      const double P = at_n.at(at_n.g, i) * jw, Q = at_half.at(at_half.g_t, i) * jw,
                   R = at_half.at(at_half.g, i) * jw;
      A[l * n] = h * h * P + h * Q;
      A[l * n + p] = h * R;
      A[(p + l) * n] = 2. * h * P;
      // Contact rows, dropper columns (G_t of a dropper is 0: Q_d = 0).
      const double g1 = at_next.at(at_next.g, i) * jw,
                   g1t = at_next.at(at_next.g_t, i) * jw;
      A[l] = h * h * g1;
      A[p + l] = h * g1;
      A[p * n + l] = h * h * g1t + 2. * h * g1;
      A[p * n + p + l] = h * g1t;
    }
    solve_small(n, A, b);
    // The contact's corrections.
    const double eta = b[0], mu = b[p];
    for (int i = window_first; i <= window_last; ++i)
    {
      const double P = at_n.at(at_n.g, i) * jw, Q = at_half.at(at_half.g_t, i) * jw,
                   R = at_half.at(at_half.g, i) * jw;
      nqw[i] += h * h * eta * P + h * eta * Q + h * mu * R;
      nvw[i] += 2. * h * eta * P;
    }
    for (int r = 0; r < 2; ++r)
    {
      const double P = -mp[2 * r]; // M_p^-1 applied to -e_head
      q_new.p[r] += (h * h * eta + h * mu) * P;
      v_new.p[r] += 2. * h * eta * P;
    }
    for (int l = 1; l < p; ++l)
      correct_dropper(droppers[near[l - 1]], b[l], b[p + l], nqc, nqw, nvc, nvw);
  }

  /// q += M^-1 G_d^T (h^2 eta + h mu), v += M^-1 G_d^T 2 h eta for dropper @p d.
  void correct_dropper(const Dropper& d, const double eta, const double mu, double* nqc,
                       double* nqw, double* nvc, double* nvw) const
  {
    const double h = dt, fq = h * h * eta + h * mu, fv = 2. * h * eta;
    nqw[d.node] += fq * jw;
    nqc[d.node] -= fq * jc;
    nvw[d.node] += fv * jw;
    nvc[d.node] -= fv * jc;
  }

  /// A dropper away from the contact: its 2x2 system [h^2 S, h S; 2h S, 0] alone.
  void project_other_droppers()
  {
    double* nqc = q_new.c.data() + 2;
    double* nqw = q_new.w.data() + 2;
    double* nvc = v_new.c.data() + 2;
    double* nvw = v_new.w.data() + 2;
    const double h = dt, S = jw + jc;
    std::size_t next = 0;
    for (unsigned int j = 0; j < droppers.size(); ++j)
    {
      if (next < near.size() && near[next] == j)
      {
        ++next;
        continue;
      }
      const Dropper& d = droppers[j];
      const int i = d.node;
      const double r_g = -(nqw[i] - nqc[i] + d.z), r_v = -(nvw[i] - nvc[i]);
      const double eta = r_v / (2. * h * S), mu = (r_g - h * h * S * eta) / (h * S);
      correct_dropper(d, eta, mu, nqc, nqw, nvc, nvw);
    }
  }

  double dt, t = 0.;
  SmoothedDelta delta;
  FusedContact contact;
  int N = 0;
  unsigned int oc = 0, ow = 0, op = 0;
  double kc0 = 0., kc1 = 0., kw0 = 0., kw0_end = 0., kw1 = 0., kw2 = 0.;
  std::vector<double> extra_fc, extra_fw; ///< f minus its uniform part (ghosts too)
  std::vector<PointLoad> point_loads;
  double fc = 0., fw = 0., half_dc = 0., half_dw = 0.;
  double ic = 0., iw = 0., jc = 0., jw = 0.; ///< (m + dt/2 d)^-1 and m^-1
  double fp[2] = {0., 0.}, kp[4] = {}, half_dp[4] = {};
  std::array<double, 4> wp{}, mp{}; ///< pantograph (M + dt/2 D)^-1 and M^-1
  std::vector<Dropper> droppers;
  std::vector<unsigned int> near; ///< droppers under the contact's rows
  Wires q, q_new, v, v_prev, v_new;
  Row at_n, at_half, at_next;
  int window_first = 0, window_last = -1;
  std::array<double, 2> head_free{};
  double lambda_contact = 0.;
};
} // namespace pantocat::bench
