#pragma once

#include <pantocat/scene/scene_effect.h>

namespace pantocat
{
/**
 * A prescribed constant force F moving with the pantograph, x_p(t) = x_p(0) + v_p t:
 * the load F F_w(t)^T of (33) on the contact wire (smoothed delta_eps or point
 * load, Sec. 4.1). The classical moving-load problem, without a pantograph body.
 */
class MovingForce : public SceneEffect
{
public:
  std::string name() const override;
  bool enabled(const SceneParameters& scene, const CatenaryParameters&) const override;
  bool part_of_catenary() const override { return false; }
  void add_constraints(SceneAssembly& assembly) const override;
  std::string describe(const SceneAssembly& assembly) const override;
};
} // namespace pantocat
