#pragma once

#include <pantocat/scene/scene_effect.h>

#include <deal.II/lac/vector.h>

#include <vector>

namespace pantocat
{
/**
 * Weights of the suspension clamps and half droppers at each dropper,
 * (m_s + l_j rho_d A_d / 2) g, as point loads on both wires, Eq. (4).
 */
class ClampAndDropperMasses : public SceneEffect
{
public:
  std::string name() const override;
  bool enabled(const SceneParameters& scene, const CatenaryParameters&) const override;
  void add_terms(SceneAssembly& assembly) const override;
  std::string describe(const SceneAssembly& assembly) const override;
};

/**
 * Adds to @p load (of @p system, built on @p space) the change of the load f
 * in (17) when the dropper lengths l_j change by @p length_changes: the
 * dropper weights l_j rho_d A_d g / 2 on each wire, Eq. (4), are linear in
 * l_j. Nothing if the scene has no ClampAndDropperMasses. The static design
 * (design_catenary()) iterates on the lengths with one assembled system.
 */
void add_dropper_weight_change(const SceneParameters& scene,
                               const CatenaryParameters& catenary,
                               const CatenaryDiscretisation& space,
                               const SemiDiscreteSystem& system,
                               const std::vector<double>& length_changes,
                               dealii::Vector<double>& load);
} // namespace pantocat
