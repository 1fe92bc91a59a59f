#pragma once

#include <pantocat/lac/sparse_row.h>

#include <algorithm>
#include <string>

namespace pantocat
{
/**
 * A scalar constraint g(t, q) = G(t) q + z(t), linear in q as all constraints
 * of the benchmark (Sec. 5.1), with the time derivatives that the hidden
 * constraints of (37), (38) need:
 *   velocity level      dg/dt   = G_t q + G v + z_t,
 *   acceleration level  d2g/dt2 = G_tt q + 2 G_t v + G a + z_tt.
 */
struct ConstraintState
{
  SparseRow G, G_t, G_tt;
  double z = 0., z_t = 0., z_tt = 0.;

  template <typename VectorType>
  double position_residual(const VectorType& q) const
  {
    return G.dot(q) + z;
  }
  template <typename VectorType>
  double velocity_residual(const VectorType& q, const VectorType& v) const
  {
    return G_t.dot(q) + G.dot(v) + z_t;
  }
};

/**
 * The compliance of a constraint: a stiffness k [N/m] and a damping c [N s/m]
 * that make it a force law instead of a rigid condition. k = 0 (the default)
 * means rigid.
 */
struct Compliance
{
  double stiffness = 0.; ///< k > 0: compliant; 0: rigid
  double damping = 0.;   ///< c >= 0, only for compliant constraints
};

/**
 * One constraint of the semi-discrete system (35): a dropper (31) or the
 * contact (32). Unilateral constraints ask g >= 0 with multiplier lambda >= 0
 * and complementarity (6), (9); bilateral ones g = 0.
 *
 * Compliant constraints (Compliance::stiffness k > 0) are forces, not
 * conditions: with the gap g = G q + z and its rate dg/dt = G_t q + G v + z_t,
 *
 *   unilateral:  lambda = max(0, -k g - c dg/dt) if g < 0, else 0
 *                (an elastic tension-only dropper, penalty contact),
 *   bilateral:   lambda = -k g - c dg/dt            (a linear spring),
 *
 * acting as G^T lambda in (35) like a rigid constraint's multiplier. They are
 * of index 1: no hidden constraints, never in the GGL stabilisation (38) nor
 * in the active set of Sec. 5.3; the rigid constraint is their limit k -> oo.
 * Integrators report lambda where a rigid constraint's multiplier would be,
 * and DynamicState::active says whether the force law is *engaged* (lambda > 0
 * for a unilateral one; always for a bilateral one).
 */
class Constraint
{
public:
  enum class Kind
  {
    bilateral,
    unilateral
  };

  /// Throws InputError for k < 0, c < 0, c > 0 with k = 0, or non-finite values.
  Constraint(std::string name, Kind kind, Compliance compliance = {});
  virtual ~Constraint() = default;

  const std::string& name() const { return label; }
  Kind kind() const { return kind_; }
  bool is_unilateral() const { return kind_ == Kind::unilateral; }
  /// True for a force law (k > 0), false for a rigid constraint.
  bool is_compliant() const { return compliance_.stiffness > 0.; }
  /// True for a rigid unilateral constraint: one of the active set of Sec. 5.3.
  bool is_rigid_unilateral() const { return is_unilateral() && !is_compliant(); }
  const Compliance& compliance() const { return compliance_; }

  /**
   * The force law's value -k g - c dg/dt of a compliant constraint for gap
   * @p gap and gap rate @p rate, before the max() of a unilateral one.
   */
  double trial_force(const double gap, const double rate) const
  {
    return -compliance_.stiffness * gap - compliance_.damping * rate;
  }
  /**
   * The force of a compliant constraint: -k g - c dg/dt for a bilateral one;
   * for a unilateral one max(0, -k g - c dg/dt) if g < 0, else 0. Never
   * negative for a unilateral one.
   */
  double compliant_force(const double gap, const double rate) const
  {
    const double f = trial_force(gap, rate);
    if (!is_unilateral())
      return f;
    return gap < 0. && f > 0. ? f : 0.;
  }
  /// Strain energy of the spring: k/2 min(g, 0)^2 (unilateral), k/2 g^2 (bilateral).
  double strain_energy(const double gap) const
  {
    const double e = is_unilateral() ? std::min(gap, 0.) : gap;
    return 0.5 * compliance_.stiffness * e * e;
  }

  /// True when G or z change with time (the moving contact).
  virtual bool depends_on_time() const = 0;

  /**
   * G(t), z(t) and their time derivatives up to @p max_order (0, 1 or 2);
   * the higher ones are left as they are.
   */
  virtual void evaluate(double t, ConstraintState& state,
                        unsigned int max_order = 2) const = 0;

private:
  std::string label;
  Kind kind_;
  Compliance compliance_;
};

/// A constraint with constant G and z: a dropper, Eq. (31).
class FixedConstraint : public Constraint
{
public:
  FixedConstraint(std::string name, Kind kind, SparseRow row, double offset,
                  Compliance compliance = {})
      : Constraint(std::move(name), kind, compliance), row(std::move(row)), offset(offset)
  {
  }
  bool depends_on_time() const override { return false; }
  void evaluate(double, ConstraintState& state, unsigned int = 2) const override
  {
    state.G = row;
    state.G_t.clear();
    state.G_tt.clear();
    state.z = offset;
    state.z_t = state.z_tt = 0.;
  }

private:
  SparseRow row;
  double offset;
};
} // namespace pantocat
