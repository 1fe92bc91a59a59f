#pragma once

#include <pantocat/scene/scene_effect.h>

namespace pantocat
{
/**
 * The contact of pantograph head and contact wire, (26)/(32): Delta_p =
 * F_w(t) q_w - b(q_MBS) >= 0 (or = 0), through ContactConstraint; on a rigid
 * wire at height 0, Delta_p = -b(q_MBS).
 */
class PantographContact : public SceneEffect
{
public:
  std::string name() const override;
  bool enabled(const SceneParameters& scene, const CatenaryParameters&) const override;
  bool part_of_catenary() const override { return false; }
  void add_constraints(SceneAssembly& assembly) const override;
  std::string describe(const SceneAssembly& assembly) const override;
};
} // namespace pantocat
