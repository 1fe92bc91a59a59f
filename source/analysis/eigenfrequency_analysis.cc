#include <pantocat/analysis/banded_eigenvalues.h>
#include <pantocat/analysis/eigenfrequency_analysis.h>

#include <deal.II/base/numbers.h>

#include <algorithm>
#include <cmath>

namespace pantocat
{
std::vector<SubsystemFrequencies>
compute_extreme_frequencies(const CatenaryDiscretisation& discretisation)
{
  std::vector<SubsystemFrequencies> result;
  for (const Wire wire : {Wire::carrier, Wire::contact_wire})
  {
    BlockOperator op;
    discretisation.assemble(wire, op);
    const double two_pi = 2. * dealii::numbers::PI;
    result.push_back(
        {to_string(discretisation.method()), op.name,
         std::sqrt(smallest_generalized_eigenvalue(op.stiffness, op.mass)) / two_pi,
         std::sqrt(largest_generalized_eigenvalue(op.stiffness, op.mass)) / two_pi});
  }
  return result;
}

double explicit_step_size_limit(const std::vector<SubsystemFrequencies>& frequencies)
{
  double f_max = 0.;
  for (const auto& f : frequencies)
    f_max = std::max(f_max, f.f_max_hz);
  return 2. / (2. * dealii::numbers::PI * f_max);
}

double PaperTable1::f_min(const std::string&, const std::string& subsystem)
{
  return subsystem == "carrier" ? 3.9528 : 2.9631;
}

double PaperTable1::f_max(const std::string& discretisation, const std::string& subsystem)
{
  if (discretisation == "fem")
    return subsystem == "carrier" ? 2.1793e3 : 5.9257e4;
  return subsystem == "carrier" ? 1.2582e3 : 4.8088e3;
}
} // namespace pantocat
