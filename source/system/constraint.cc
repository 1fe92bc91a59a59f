#include <pantocat/base/input_error.h>
#include <pantocat/system/constraint.h>

#include <cmath>

namespace pantocat
{
Constraint::Constraint(std::string name, const Kind kind, const Compliance compliance)
    : label(std::move(name)), kind_(kind), compliance_(compliance)
{
  const double k = compliance.stiffness, c = compliance.damping;
  require(std::isfinite(k) && k >= 0., "stiffness of constraint '" + label + "'", k,
          "must be finite and >= 0 N/m (0: rigid)");
  require(std::isfinite(c) && c >= 0., "damping of constraint '" + label + "'", c,
          "must be finite and >= 0 N s/m");
  require(c == 0. || k > 0., "damping of constraint '" + label + "'", c,
          "a rigid constraint (stiffness 0) has no damping");
}
} // namespace pantocat
