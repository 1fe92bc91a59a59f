#pragma once

#include <pantocat/scene/scene_effect.h>

namespace pantocat
{
/**
 * Bending stiffness of the elastic wires: E I int v'' w'' dx in the weak form
 * (16), the operator K_w of (30). The paper's contact wire is a beam; its
 * carrier a string, which a scene may stiffen (Messenger bending, with C1
 * Hermite elements or FDM).
 */
class WireBending : public SceneEffect
{
public:
  std::string name() const override;
  bool enabled(const SceneParameters& scene, const CatenaryParameters&) const override;
  void add_terms(SceneAssembly& assembly) const override;
  std::string describe(const SceneAssembly& assembly) const override;
};
} // namespace pantocat
