#include <pantocat/analysis/elasticity_parameters.h>
#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace pantocat
{
void ElasticityParameters::declare_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Elasticity");
  prm.declare_entry("Span", "0", dealii::Patterns::Integer(0),
                    "Mode = static: the span (1 = the first of the section) whose "
                    "static elasticity is computed: the contact wire's static uplift "
                    "per unit upward point force [mm/N], droppers free to slacken, no "
                    "pantograph; writes elasticity.csv and elasticity.png. 0: off.");
  prm.declare_entry("Points", "21", dealii::Patterns::Integer(0),
                    "Number of load points, equally spaced over the span, both "
                    "supports included (>= 2).");
  prm.declare_entry("Forces", "100, 200",
                    dealii::Patterns::List(dealii::Patterns::Double(), 1),
                    "Upward point forces F [N] (> 0, distinct): each is applied alone "
                    "at each point; one elasticity column per force.");
  prm.leave_subsection();
}

void ElasticityParameters::parse_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Elasticity");
  span = prm.get_integer("Span");
  points = prm.get_integer("Points");
  forces = dealii::Utilities::string_to_double(
      dealii::Utilities::split_string_list(prm.get("Forces")));
  prm.leave_subsection();
}

void ElasticityParameters::check(const unsigned int n_spans) const
{
  require(span <= n_spans, "Elasticity/Span", span,
          "the section has " + std::to_string(n_spans) +
              (n_spans == 1 ? " span" : " spans") + "; allowed 0 (off) or 1.." +
              std::to_string(n_spans));
  require(points >= 2, "Elasticity/Points", points,
          "must be >= 2 (equally spaced over the span, both supports included)");
  for (const double f : forces)
    require(std::isfinite(f) && f > 0., "Elasticity/Forces", list_to_string(forces),
            "every force must be a number > 0 [N] (an upward load)");
  // Compared as written: each names a column.
  std::vector<std::string> names;
  for (const double f : forces)
    names.push_back(number_to_string(f));
  std::sort(names.begin(), names.end());
  require(std::adjacent_find(names.begin(), names.end()) == names.end(),
          "Elasticity/Forces", list_to_string(forces),
          "the forces must differ (one column of elasticity.csv each)");
}
} // namespace pantocat
