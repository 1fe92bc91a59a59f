#pragma once

#include <deal.II/base/parameter_handler.h>

#include <vector>

namespace pantocat
{
/**
 * Subsection Elasticity: the static check of a catenary (Mode = static). The
 * contact wire's static uplift per unit upward force, e = 1000 u / F
 * [mm/N], at equally spaced points of one span, the droppers free to
 * slacken, no pantograph (doc/elasticity.md).
 */
struct ElasticityParameters
{
  unsigned int span = 0;    ///< 1-based span of the section; 0: no static check
  unsigned int points = 21; ///< load points over the span, both supports included
  std::vector<double> forces = {100., 200.}; ///< upward forces F [N]

  bool enabled() const { return span > 0; }

  static void declare_parameters(dealii::ParameterHandler& prm);
  void parse_parameters(dealii::ParameterHandler& prm);
  /**
   * Refuses a span outside 0..@p n_spans, fewer than 2 points, a force that
   * is not a finite number > 0, and a force given twice; throws InputError
   * naming the parameter, the value and what is allowed.
   */
  void check(unsigned int n_spans) const;
};
} // namespace pantocat
