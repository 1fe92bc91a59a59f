#pragma once

#include <pantocat/scene/scene_effect.h>

namespace pantocat
{
/**
 * Rayleigh damping of the catenary, D = alpha M + beta K on each wire, with M
 * and K as assembled so far: the wires' mass, tension and bending, the point
 * masses and the support springs, without droppers and pantographs (the form
 * railway codes use; the paper's viscous beta w_t is ViscousDamping). It is
 * registered after every effect that adds to the wires' M or K.
 */
class RayleighDamping : public SceneEffect
{
public:
  std::string name() const override;
  bool enabled(const SceneParameters& scene,
               const CatenaryParameters& catenary) const override;
  void add_terms(SceneAssembly& assembly) const override;
  std::string describe(const SceneAssembly& assembly) const override;
};
} // namespace pantocat
