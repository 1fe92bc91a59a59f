#pragma once

#include <pantocat/constrained/constrained_operator.h>
#include <pantocat/time/time_integrator.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace pantocat
{
/**
 * What the rest of the program knows of a time integrator: its name (the
 * value of Time integration/Integrator), how to make it, and the properties
 * that checks and outputs ask about. A new integrator is one file pair whose
 * class provides such an entry, plus one line in registered_integrators().
 */
struct IntegratorEntry
{
  std::string name;        ///< e.g. "half-explicit"
  std::string description; ///< one sentence for the parameter documentation
  /// Explicit in the unknowns: stable only for dt < 2/omega_max (refused above).
  bool explicit_step_limit = false;
  /// save() and load() continue a run bit for bit.
  bool writes_checkpoints = true;
  /// Switches of unilateral constraints located in time (root finding).
  bool locates_events = false;
  std::function<std::unique_ptr<TimeIntegrator>(const SemiDiscreteSystem&,
                                                const TimeIntegrationParameters&)>
      create;
  /**
   * For an integrator whose linear algebra is ConstrainedOperator's: make it
   * with the implementation @p algebra (create() makes it with the fast
   * one; the tests compare it with the reference). Empty for the others.
   */
  std::function<std::unique_ptr<TimeIntegrator>(
      const SemiDiscreteSystem&, const TimeIntegrationParameters&, LinearAlgebra)>
      create_with_linear_algebra;
};

/// Every integrator, in the order of the parameter documentation.
const std::vector<IntegratorEntry>& registered_integrators();

/// The entry named @p name; throws InputError naming Time integration/Integrator.
const IntegratorEntry& integrator_entry(const std::string& name);

/// "half-explicit|bdf2|..." for Patterns::Selection.
std::string integrator_selection();

/// The descriptions of all integrators, "name: description; ..." for the documentation.
std::string integrator_documentation();
} // namespace pantocat
