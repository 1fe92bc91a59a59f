#pragma once

#include <pantocat/scene/scene_effect.h>

namespace pantocat
{
/**
 * The lumped-mass pantograph (10) as a body: its M, D, K and static force.
 */
class PantographBody : public SceneEffect
{
public:
  std::string name() const override;
  bool enabled(const SceneParameters& scene, const CatenaryParameters&) const override;
  bool part_of_catenary() const override { return false; }
  void add_bodies(SceneAssembly& assembly) const override;
  std::string describe(const SceneAssembly& assembly) const override;
};
} // namespace pantocat
