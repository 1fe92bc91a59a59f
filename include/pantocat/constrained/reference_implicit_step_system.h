#pragma once

#include <pantocat/constrained/implicit_step_system.h>
#include <pantocat/constrained/reference_constrained_operator.h>

#include <deal.II/lac/vector.h>

#include <map>
#include <utility>
#include <vector>

namespace pantocat
{
/**
 * The plain ImplicitStepSystem, the oracle of the fast one. The solution is
 * the base solution (all multipliers 0) plus one response per multiplier:
 * for lambda_i, eta_i or mu_i the q, v, a that a unit value of it alone
 * gives,
 *
 *   lambda: q = S^-1 G^T,                       v = c q,      a = c v,
 *   eta:    q = S^-1 (G^T + c G_t^T + D Z),     v = c q - Z,  a = c v - Y,
 *   mu:     q = S^-1 (c G^T + D Y),             v = c q - Y,  a = c v,
 *
 * with Y = M^-1 G^T, Z = M^-1 G_t^T, each by full solves
 * (ReferenceConstrainedOperator: UMFPACK); those of constant rows once, the
 * others at every start(). The multiplier system is the equations' levels of
 * the responses, assembled dense and solved by LAPACK's LU factorisation.
 * No truncation, no settling, no structure.
 */
class ReferenceImplicitStepSystem : public ImplicitStepSystem
{
public:
  ReferenceImplicitStepSystem(const SemiDiscreteSystem& system, double c);

  void start(const std::vector<ConstraintState>& rows, double t,
             const dealii::Vector<double>& rho_q, const dealii::Vector<double>& rho_v,
             const std::vector<bool>* held, const NextHistory* next,
             bool continued) override;
  void solve(const std::vector<Role>& roles, dealii::Vector<double>& q,
             dealii::Vector<double>& v, dealii::Vector<double>& a,
             std::vector<double>& lambda) override;
  void take_next_history(dealii::Vector<double>& rho_q,
                         dealii::Vector<double>& rho_v) override;

  /// q, v, a of one solution part (the base, or one multiplier's response).
  struct Response
  {
    dealii::Vector<double> q, v, a;
  };

  /// A multiplier (kind 0 lambda, 1 eta, 2 mu) or equation (level 0, 1, 2,
  /// or 3: the force law) of one constraint.
  struct Slot
  {
    unsigned int constraint, kind;
  };

private:
  /// The multipliers of @p unknowns from @p equations, dense (LAPACK LU).
  dealii::Vector<double> multipliers(const std::vector<Slot>& unknowns,
                                     const std::vector<Slot>& equations);
  /// The response of multiplier @p kind (0 lambda, 1 eta, 2 mu) of constraint @p i.
  const Response& response(unsigned int i, unsigned int kind);

  ReferenceConstrainedOperator S, M;
  Response base;
  std::map<std::pair<unsigned int, unsigned int>, Response> responses;
  dealii::Vector<double> next_rho_q, next_rho_v;
};
} // namespace pantocat
