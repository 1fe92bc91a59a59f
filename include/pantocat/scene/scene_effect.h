#pragma once

#include <pantocat/scene/scene_assembly.h>

#include <string>

namespace pantocat
{
/**
 * One effect of a scene: a body, a term of the weak form, a load or
 * a constraint. The scene builder asks every registered effect whether the
 * scene enables it, and lets the enabled ones contribute in three phases:
 *  1. add_bodies():      a body's operator (its unknowns and mass);
 *  2. add_terms():       terms added to the bodies' operators (stiffness,
 *                        damping, loads);
 *  3. add_constraints(): constraints and time-dependent loads of the system.
 * An effect that is not enabled is never called: it is neither assembled
 * nor integrated. A new effect is one class (a file pair) and one line in
 * registered_scene_effects(); the integrators see only the resulting
 * SemiDiscreteSystem.
 */
class SceneEffect
{
public:
  virtual ~SceneEffect() = default;

  /// Short name, e.g. "gravity".
  virtual std::string name() const = 0;
  /// True if @p scene (with the section @p catenary) has this effect.
  virtual bool enabled(const SceneParameters& scene,
                       const CatenaryParameters& catenary) const = 0;
  /**
   * False for the pantograph's effects: the static catenary that the initial
   * state starts from (Sec. 2.2) is built without them.
   */
  virtual bool part_of_catenary() const { return true; }

  virtual void add_bodies(SceneAssembly&) const {}
  virtual void add_terms(SceneAssembly&) const {}
  virtual void add_constraints(SceneAssembly&) const {}

  /// One line for the start-up report: what the effect adds, in the paper's terms.
  virtual std::string describe(const SceneAssembly& assembly) const = 0;
};
} // namespace pantocat
