#pragma once

#include <pantocat/pantograph/pantograph_parameters.h>
#include <pantocat/system/constraint.h>

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace pantocat
{
/// A wire that moves (a body of the semi-discrete system) or stays where it hangs.
enum class WireModel
{
  elastic, ///< a string (carrier) or beam (contact wire), Eq. (2)
  rigid    ///< fixed: the carrier at height l_c, the contact wire at height 0
};

enum class DropperModel
{
  unilateral, ///< may slacken: Delta_d >= 0, Sec. 5.3
  bilateral,  ///< always taut: Delta_d = 0, Eq. (4)
  elastic,    ///< tension-only spring: force k_d max(-Delta_d, 0), unstretched length l_j
  absent
};

/// The Scene/Droppers value that selects @p model.
std::string to_string(DropperModel model);

/**
 * One pantograph of a scene: its model, how it meets the contact wire, and its
 * data and motion (Sec. 2.2). Pantograph 1 is Scene/Pantograph, Scene/Contact
 * and Scene/Moving force with subsection Pantograph; pantograph k >= 2 is
 * subsection Pantograph k, whose entries default to pantograph 1's values.
 */
struct PantographCase
{
  /// A registered lumped-mass model (registered_pantograph_models()), "moving
  /// force" (a prescribed constant force, no body) or "absent".
  std::string model = "two-mass";
  Constraint::Kind contact = Constraint::Kind::unilateral;
  /// Contact = penalty: the compliant unilateral law lambda_p = max(0, -k_c g -
  /// c_c dg/dt) (stiffness > 0); rigid (stiffness 0) otherwise.
  Compliance contact_compliance;
  double moving_force = 100.; ///< [N], upwards, for model = moving force
  PantographParameters parameters;

  /// A lumped-mass body in contact with the wire.
  bool has_body() const;
  bool is_moving_force() const { return model == "moving force"; }
  bool is_absent() const { return model == "absent"; }
  /// "Scene/Pantograph" for pantograph 1, "Pantograph k/Model" for the others.
  std::string model_parameter() const;
  /// The full name of its contact entry @p entry ("Contact damping", ...):
  /// Scene/<entry> for pantograph 1, Pantograph k/<entry> for pantograph k.
  std::string contact_entry(const std::string& entry) const;
  /// The Scene/Contact value: unilateral, bilateral or penalty.
  std::string contact_law() const;
};

/// How the run starts.
enum class InitialShape
{
  static_equilibrium, ///< the static catenary under its loads (Secs. 2.2 and 6)
  rest,               ///< undeformed and at rest (no constraints allowed)
  sine_mode           ///< contact wire w = A sin(k pi x / L), at rest (no constraints)
};

/// How a scene with pantographs on the wire starts (Run/Start, doc/dynamics.md).
enum class Start
{
  /// Catenary and pantographs at rest in the static equilibrium of the whole
  /// system, each contact pressed by its pantograph (static_initial_state()).
  static_equilibrium,
  /// The paper's start (13) with Pantograph/Initial contact force and Initial
  /// offset (consistent_initial_state()), for the paper's cases.
  paper
};

/**
 * A scene: which bodies exist and which effects act. The defaults
 * are the paper's benchmark (Sec. 6). Every effect the scene leaves out is
 * neither assembled nor integrated.
 */
struct SceneParameters
{
  WireModel carrier = WireModel::elastic;
  WireModel contact_wire = WireModel::elastic;
  bool carrier_tension = true;
  bool contact_wire_tension = true;
  bool contact_wire_bending = true;
  bool carrier_bending = false; ///< the paper's carrier is a string
  bool gravity = true;
  bool damping = true;
  bool clamp_and_dropper_masses = true;
  DropperModel droppers = DropperModel::unilateral;
  /// The pantographs, in the order of their blocks and contacts; numbers are data.
  std::vector<PantographCase> pantographs{PantographCase{}};
  /**
   * s [m] (Scene/Pantograph spacing): 0, or pantograph k >= 2 runs (k - 1) s
   * behind pantograph 1 at its speed (initial and final positions derived by
   * parse_parameters(), not read).
   */
  double pantograph_spacing = 0.;
  InitialShape initial_shape = InitialShape::static_equilibrium;
  Start start =
      Start::static_equilibrium;   ///< Run/Start, for InitialShape::static_equilibrium
  unsigned int initial_mode = 1;   ///< k of the sine mode
  double initial_amplitude = 0.01; ///< A of the sine mode [m]

  /// True if some pantograph is a lumped-mass body in contact with the wire.
  bool has_pantograph_body() const;
  /// True if some pantograph is a prescribed moving force.
  bool has_moving_force() const;
  bool has_droppers() const { return droppers != DropperModel::absent; }
  /**
   * The classical moving-load problem: a moving force on the elastic contact
   * wire alone (no droppers), no gravity, no damping, from rest. Its series
   * solution (MovingLoadSeries) is the exact reference.
   */
  bool is_classical_moving_load() const
  {
    return pantographs.size() == 1 && pantographs[0].is_moving_force() &&
           !has_droppers() && !gravity && !damping &&
           initial_shape == InitialShape::rest && contact_wire == WireModel::elastic;
  }

  /**
   * Declares subsection Scene and the pantographs' subsections: Pantograph,
   * and Pantograph 2 .. Pantograph @p n_pantographs, whose entries default to
   * @p first (pantograph 1 as read in a first pass over the file).
   */
  static void declare_parameters(dealii::ParameterHandler& prm,
                                 unsigned int n_pantographs = 1,
                                 const PantographCase& first = {});
  /// Reads Scene and every pantograph's subsection; with a pantograph spacing s > 0
  /// pantograph k >= 2 gets x_{p,0} - (k - 1) s, x_p(t_e) - (k - 1) s and v_p of
  /// pantograph 1.
  void parse_parameters(dealii::ParameterHandler& prm);
  /// Declares subsection @p subsection of a pantograph k >= 2 with @p first's values.
  static void declare_further_pantograph(dealii::ParameterHandler& prm,
                                         const std::string& subsection,
                                         const PantographCase& first);
  /// Scene/Number of pantographs as given in @p prm (declared by declare_parameters()).
  static unsigned int number_of_pantographs(dealii::ParameterHandler& prm);
  /// Cross-checks (a wire without stiffness, a moving force on a rigid wire, ...);
  /// throws InputError naming the parameter.
  void check() const;
  /**
   * Refuses a pantograph spacing < 0, or one that puts a pantograph outside
   * (@p margin, @p length - @p margin) at some time of the run (the wires'
   * domain less the load's half-width).
   */
  void check_spacing(double length, double margin) const;
};

} // namespace pantocat
