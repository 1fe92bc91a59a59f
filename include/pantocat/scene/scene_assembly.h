#pragma once

#include <pantocat/base/contact_point_motion.h>
#include <pantocat/catenary/catenary_parameters.h>
#include <pantocat/pantograph/pantograph_model.h>
#include <pantocat/scene/scene_parameters.h>
#include <pantocat/space/catenary_discretisation.h>
#include <pantocat/system/block_operator.h>
#include <pantocat/system/semi_discrete_system.h>

#include <memory>

#include <deal.II/base/numbers.h>

#include <string>
#include <vector>

namespace pantocat
{
/**
 * One pantograph of a scene as the scene builds it: its data, its lumped-mass
 * model (nullptr for a moving force or an absent pantograph), its motion and
 * the names of its block and contact. With one pantograph the names are
 * "pantograph" and "contact"; with several, "pantograph k" and "contact k".
 */
struct ScenePantograph
{
  const PantographCase* data = nullptr;
  std::shared_ptr<const PantographModel> model;
  ContactPointMotion motion;
  std::string block;         ///< name of its block of unknowns
  std::string contact;       ///< name of its contact constraint
  std::string column_suffix; ///< "" with one pantograph, "[k]" with several
  /**
   * Index of its contact constraint in the system, or invalid_unsigned_int;
   * in a line of several sections, its contact with the wire it touches at
   * t = 0.
   */
  unsigned int contact_index = dealii::numbers::invalid_unsigned_int;
  /// Every contact constraint of it, one per contact wire (section) it can touch.
  std::vector<unsigned int> wire_contacts;

  bool has_contact() const
  {
    return contact_index != dealii::numbers::invalid_unsigned_int;
  }
};

/// The pantographs of @p scene with their models made from the registry.
std::vector<ScenePantograph> make_scene_pantographs(const SceneParameters& scene);

/// One tension section of a scene's line: its data and its discretisation.
struct SceneSection
{
  const CatenaryParameters* catenary = nullptr;
  const CatenaryDiscretisation* space = nullptr;
};

/**
 * What the effects of a scene build together, in three phases (SceneEffect):
 * the bodies' operators, the terms added to them, then the semi-discrete
 * system (35) with its constraints and time-dependent loads.
 *
 * A line holds several tension sections; the builder lets the catenary's
 * effects contribute to each section in turn (select_section()), so that an
 * effect sees one section through catenary() and space(). The pantographs'
 * effects see the whole line through sections.
 */
struct SceneAssembly
{
  SceneAssembly(const SceneParameters& scene, std::vector<SceneSection> sections,
                std::vector<ScenePantograph> pantographs)
      : scene(scene), sections(std::move(sections)), pantographs(std::move(pantographs))
  {
  }

  const SceneParameters& scene;
  /// The tension sections along the line, in order (one for a single section).
  const std::vector<SceneSection> sections;
  /// The section the catenary's effects contribute to now.
  const CatenaryParameters& catenary() const { return *sections[current].catenary; }
  const CatenaryDiscretisation& space() const { return *sections[current].space; }
  void select_section(const unsigned int k) { current = k; }
  /// @p name of a constraint of the current section, after the section's name in a line.
  std::string constraint_name(const std::string& name) const;
  /// Every pantograph of the scene (the contact effect sets contact_index).
  std::vector<ScenePantograph> pantographs;

  /// Phase 1 and 2: the operators of the bodies, in the order of the unknowns.
  std::vector<BlockOperator> bodies;
  /// The body named @p name ("carrier", "contact wire", "pantograph", ...), or nullptr.
  BlockOperator* body(const std::string& name);
  /// The current section's body of @p wire, or nullptr.
  BlockOperator* wire_body(Wire wire);
  /// The current section's body of stitch wires, or nullptr.
  BlockOperator* stitch_body();

  /// Phase 3: the system, its blocks set from the bodies.
  SemiDiscreteSystem system;
  std::vector<unsigned int> dropper_indices;
  std::vector<unsigned int> support_indices; ///< the fixed carrier supports' constraints

  /// The data of @p wire (CatenaryParameters).
  const WireParameters& wire_parameters(Wire wire) const;
  /// Phase 1: @p wire as a body (its unknowns and mass), wide enough for bending.
  void add_wire_body(Wire wire, bool with_bending);
  /// Phase 2: adds @p terms to @p wire's operator; nothing if the wire is rigid.
  void add_wire_terms(Wire wire, const WireTerms& terms);

  /// "smoothed delta_eps, eps = 0.2 m" or "point load": how F_w of (33) spreads a force.
  std::string load_shape() const;

  /// Global row of the displacement of @p wire at @p x (empty if the wire is rigid).
  SparseRow wire_row(Wire wire, double x) const;

  /**
   * Phase 2: a point mass @p m on @p wire at @p x: m H^T H added to the
   * wire's mass matrix (H = the wire's point row at x); on a diagonal (FDM)
   * mass matrix lumped to m H_i on the diagonal, so that it stays diagonal
   * (H sums to 1). Nothing if the wire is rigid.
   */
  void add_point_mass(Wire wire, double x, double m);
  /// Phase 2: a vertical spring @p k to the ground on @p wire at @p x: k H^T H in K.
  void add_point_spring(Wire wire, double x, double k);
  /// Phase 2: a vertical point force @p force (upward > 0) on @p wire at @p x: F H^T.
  void add_point_force(Wire wire, double x, double force);

  /**
   * Global row of the upper end of dropper @p j (dropper_upper_row()): the
   * carrier's at x_j, or its stitch wire's in a stitched catenary.
   */
  SparseRow dropper_upper_row(unsigned int j) const;
  /**
   * Phase 2: a point mass @p m and a vertical force @p force (upward > 0) at
   * the upper end of dropper @p j, on the body it hangs from (the carrier or
   * its stitch wire): as add_point_mass() and add_point_force().
   */
  void add_at_dropper_top(unsigned int j, double force, double m);

private:
  unsigned int current = 0;
};
} // namespace pantocat
