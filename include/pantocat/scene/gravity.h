#pragma once

#include <pantocat/scene/scene_effect.h>

namespace pantocat
{
/**
 * Weight of the elastic wires: the distributed load -rho A g of (2).
 */
class Gravity : public SceneEffect
{
public:
  std::string name() const override;
  bool enabled(const SceneParameters& scene, const CatenaryParameters&) const override;
  void add_terms(SceneAssembly& assembly) const override;
  std::string describe(const SceneAssembly& assembly) const override;
};
} // namespace pantocat
