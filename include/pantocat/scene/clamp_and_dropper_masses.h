#pragma once

#include <pantocat/scene/scene_effect.h>

namespace pantocat
{
/**
 * Weights of the suspension clamps and half droppers at each dropper,
 * (m_s + l_j rho_d A_d / 2) g, as point loads on both wires, Eq. (4).
 */
class ClampAndDropperMasses : public SceneEffect
{
public:
  std::string name() const override;
  bool enabled(const SceneParameters& scene, const CatenaryParameters&) const override;
  void add_terms(SceneAssembly& assembly) const override;
  std::string describe(const SceneAssembly& assembly) const override;
};
} // namespace pantocat
