#pragma once

#include <pantocat/system/sparse_row.h>

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
 * One constraint of the semi-discrete system (35): a dropper (31) or the
 * contact (32). Unilateral constraints ask g >= 0 with multiplier lambda >= 0
 * and complementarity (6), (9); bilateral ones g = 0.
 */
class Constraint
{
public:
  enum class Kind
  {
    bilateral,
    unilateral
  };

  Constraint(std::string name, Kind kind) : label(std::move(name)), kind_(kind) {}
  virtual ~Constraint() = default;

  const std::string& name() const { return label; }
  Kind kind() const { return kind_; }
  bool is_unilateral() const { return kind_ == Kind::unilateral; }

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
};

/// A constraint with constant G and z: a dropper, Eq. (31).
class FixedConstraint : public Constraint
{
public:
  FixedConstraint(std::string name, Kind kind, SparseRow row, double offset)
      : Constraint(std::move(name), kind), row(std::move(row)), offset(offset)
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
