#include <pantocat/base/input_error.h>
#include <pantocat/time/bdf2_integrator.h>
#include <pantocat/time/generalized_alpha_integrator.h>
#include <pantocat/time/half_explicit_integrator.h>
#include <pantocat/time/ida_integrator.h>
#include <pantocat/time/integrator_registry.h>

namespace pantocat
{
const std::vector<IntegratorEntry>& registered_integrators()
{
  static const std::vector<IntegratorEntry> entries{
      HalfExplicitIntegrator::registry_entry(),
      Bdf2Integrator::registry_entry(),
      GeneralizedAlphaIntegrator::registry_entry(),
      IdaIntegrator::registry_entry(),
  };
  return entries;
}

const IntegratorEntry& integrator_entry(const std::string& name)
{
  for (const IntegratorEntry& e : registered_integrators())
    if (e.name == name)
      return e;
  throw InputError("Time integration/Integrator = " + name +
                   ": no such integrator; allowed " + integrator_selection());
}

std::string integrator_selection()
{
  std::string s;
  for (const IntegratorEntry& e : registered_integrators())
    s += (s.empty() ? "" : "|") + e.name;
  return s;
}

std::string integrator_documentation()
{
  std::string s;
  for (const IntegratorEntry& e : registered_integrators())
    s += (s.empty() ? "" : "; ") + e.name + ": " + e.description;
  return s + ".";
}
} // namespace pantocat
