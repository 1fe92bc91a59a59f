#pragma once

#include <pantocat/scene/scene_effect.h>

namespace pantocat
{
/**
 * The carrier at each support between spans: fixed at its height l_c (a
 * bilateral constraint u_c(x_s) = 0, named "carrier support k"), or on a
 * vertical spring k_s preloaded with the static force of the design so that
 * the static carrier is at l_c there (k_s H^T H in K, P H^T in the load).
 */
class CarrierSupports : public SceneEffect
{
public:
  std::string name() const override;
  bool enabled(const SceneParameters& scene,
               const CatenaryParameters& catenary) const override;
  void add_terms(SceneAssembly& assembly) const override;
  void add_constraints(SceneAssembly& assembly) const override;
  std::string describe(const SceneAssembly& assembly) const override;
};
} // namespace pantocat
