#pragma once

#include <pantocat/scene/scene_effect.h>

namespace pantocat
{
/**
 * Tension of the elastic wires: T int v' w' dx in the weak form (16), the
 * operator S of (29)/(30).
 */
class WireTension : public SceneEffect
{
public:
  std::string name() const override;
  bool enabled(const SceneParameters& scene, const CatenaryParameters&) const override;
  void add_terms(SceneAssembly& assembly) const override;
  std::string describe(const SceneAssembly& assembly) const override;
};
} // namespace pantocat
