#pragma once

#include <pantocat/scene/scene_effect.h>

namespace pantocat
{
/**
 * Viscous damping beta w_t of the elastic wires, Eq. (2).
 */
class ViscousDamping : public SceneEffect
{
public:
  std::string name() const override;
  bool enabled(const SceneParameters& scene,
               const CatenaryParameters& catenary) const override;
  void add_terms(SceneAssembly& assembly) const override;
  std::string describe(const SceneAssembly& assembly) const override;
};
} // namespace pantocat
