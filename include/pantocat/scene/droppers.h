#pragma once

#include <pantocat/scene/scene_effect.h>

namespace pantocat
{
/**
 * The droppers as constraints (5)/(31),
 *   Delta_{d,j} = w_w(x_j) - w_c(x_j) + l_j >= 0 (unilateral) or = 0 (bilateral),
 * with w_c = l_c for a rigid carrier and w_w = 0 for a rigid contact wire.
 */
class Droppers : public SceneEffect
{
public:
  std::string name() const override;
  bool enabled(const SceneParameters& scene, const CatenaryParameters&) const override;
  void add_constraints(SceneAssembly& assembly) const override;
  std::string describe(const SceneAssembly& assembly) const override;
};
} // namespace pantocat
