#pragma once

#include <pantocat/scene/scene_effect.h>

namespace pantocat
{
/**
 * The stitch wires of a stitched catenary (StitchWire, doc/catenaries.md):
 * each a string of its own (StitchWireSpace, block "stitch wires") with its
 * tension T_s and mass rho_s A_s, its weight with gravity and its viscous
 * damping (Rayleigh damping adds alpha M + beta K of this block like the
 * wires'), clamped to the carrier at both ends by the bilateral constraints
 *
 *   u_s(x_a) - u_c(x_a) = 0,   u_s(x_b) - u_c(x_b) = 0
 *
 * ("stitch wire k clamp 1" and "clamp 2": the vertical motion shared there),
 * each clamp a point mass on the carrier (its weight with the clamp and
 * dropper masses, its inertia with Catenary/Point mass inertia). The
 * droppers listed for it hang from it instead of from the carrier (Droppers,
 * ClampAndDropperMasses: the carrier's row H_c of (31) is the stitch wire's).
 * A section without stitch wires assembles none of this.
 */
class StitchWires : public SceneEffect
{
public:
  std::string name() const override;
  bool enabled(const SceneParameters& scene,
               const CatenaryParameters& catenary) const override;
  void add_bodies(SceneAssembly& assembly) const override;
  void add_terms(SceneAssembly& assembly) const override;
  void add_constraints(SceneAssembly& assembly) const override;
  std::string describe(const SceneAssembly& assembly) const override;
};
} // namespace pantocat
