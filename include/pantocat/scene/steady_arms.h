#pragma once

#include <pantocat/scene/scene_effect.h>

#include <vector>

namespace pantocat
{
/**
 * Steady arms: at each support between spans, the contact wire is held by a
 * vertical spring k_sa with a lumped mass m_sa, preloaded with the static
 * force P of the design so that the static contact wire is at height 0
 * there: k_sa H^T H in K, P H^T in the load; m_sa in the mass matrix with
 * Catenary/Point mass inertia, and its weight -m_sa g H^T with gravity.
 */
class SteadyArms : public SceneEffect
{
public:
  std::string name() const override;
  bool enabled(const SceneParameters& scene,
               const CatenaryParameters& catenary) const override;
  void add_terms(SceneAssembly& assembly) const override;
  std::string describe(const SceneAssembly& assembly) const override;

  /// The positions x [m] of the steady arms of @p scene: the interior
  /// supports if it has them (enabled()), none otherwise.
  static std::vector<double> positions(const SceneParameters& scene,
                                       const CatenaryParameters& catenary);
};
} // namespace pantocat
