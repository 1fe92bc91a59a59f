#pragma once

#include <pantocat/scene/scene_effect.h>

#include <memory>
#include <string>
#include <vector>

namespace pantocat
{
/**
 * Every effect a scene may enable, in the order in which they contribute
 * (bodies: carrier, contact wire, pantograph; constraints: droppers, then the
 * contact). A new effect is registered by one line here.
 */
std::vector<std::unique_ptr<SceneEffect>> registered_scene_effects();

/// A scene's semi-discrete system (35) and what it is made of.
struct BuiltScene
{
  /// The system of the whole scene.
  SemiDiscreteSystem system;
  /// The same without the pantographs' effects (same numbering of the
  /// catenary's unknowns): the static problem of the initial state.
  SemiDiscreteSystem catenary_only;
  /// Every pantograph with its model, block and contact.
  std::vector<ScenePantograph> pantographs;
  std::vector<unsigned int> dropper_indices;
  std::vector<unsigned int> support_indices; ///< constraints of fixed carrier supports
  /// One line per active effect (describe()).
  std::vector<std::string> active_effects;
  /// Names of the registered effects the scene leaves out.
  std::vector<std::string> inactive_effects;

  /// True if some pantograph is in contact with the wire.
  bool has_contact() const;
};

/**
 * Builds the semi-discrete system of @p scene on the line of @p sections
 * (their unknowns and constraints section after section, then the
 * pantographs' and their contacts) from its enabled effects only
 * (SceneEffect's three phases); the pantographs' models come from the
 * registry. Throws InputError if the grid cannot carry the droppers.
 */
BuiltScene build_scene(const SceneParameters& scene,
                       const std::vector<SceneSection>& sections);
/// build_scene() of a line of one section.
BuiltScene build_scene(const SceneParameters& scene, const CatenaryParameters& catenary,
                       const CatenaryDiscretisation& space);

/**
 * The catenary's part of the scene alone (BuiltScene::catenary_only, with its
 * dropper_indices and support_indices; the other members empty): one assembly
 * where build_scene() makes two, for the static problems of the dropper design.
 */
BuiltScene build_catenary(const SceneParameters& scene,
                          const CatenaryParameters& catenary,
                          const CatenaryDiscretisation& space);
} // namespace pantocat
