#pragma once

#include <pantocat/scene/scene_effect.h>

namespace pantocat
{
/**
 * The carrier as a body: a string of linear Lagrange elements (FEM, Sec. 4.2) or
 * finite differences (Sec. 4.3) with mass rho_c A_c; its unknowns are u_c = w_c - l_c.
 */
class CarrierBody : public SceneEffect
{
public:
  std::string name() const override;
  bool enabled(const SceneParameters& scene, const CatenaryParameters&) const override;
  void add_bodies(SceneAssembly& assembly) const override;
  std::string describe(const SceneAssembly& assembly) const override;
};
} // namespace pantocat
