#pragma once

#include <pantocat/scene/scene_effect.h>

namespace pantocat
{
/**
 * The contact wire as a body: a beam of C1 cubic Hermite elements (FEM, Sec. 4.2)
 * or finite differences (Sec. 4.3) with mass rho_w A_w.
 */
class ContactWireBody : public SceneEffect
{
public:
  std::string name() const override;
  bool enabled(const SceneParameters& scene, const CatenaryParameters&) const override;
  void add_bodies(SceneAssembly& assembly) const override;
  std::string describe(const SceneAssembly& assembly) const override;
};
} // namespace pantocat
