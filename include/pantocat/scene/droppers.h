#pragma once

#include <pantocat/scene/scene_effect.h>

namespace pantocat
{
/**
 * The droppers as constraints (5)/(31),
 *   Delta_{d,j} = w_w(x_j) - w_c(x_j) + l_j >= 0 (unilateral) or = 0 (bilateral),
 * with w_c = l_c for a rigid carrier and w_w = 0 for a rigid contact wire.
 * Elastic droppers (DropperModel::elastic) are the compliant unilateral
 * constraint Delta_{d,j} + lambda_j / k_d >= 0, lambda_j >= 0 (Compliance):
 * a tension-only spring of stiffness k_d and unstretched length l_j, whose
 * limit k_d -> oo is the paper's inextensible dropper.
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
