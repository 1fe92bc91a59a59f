#pragma once

#include <pantocat/system/constraint.h>

#include <deal.II/base/parameter_handler.h>

#include <string>

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
  absent
};

enum class PantographType
{
  two_mass,     ///< the lumped-mass model (12)
  three_mass,   ///< a three-mass chain (head, upper and lower frame)
  moving_force, ///< a prescribed constant force moving with v_p, no pantograph body
  absent
};

/// How the run starts.
enum class InitialShape
{
  static_equilibrium, ///< the static catenary under its loads (Secs. 2.2 and 6)
  rest,               ///< undeformed and at rest (no constraints allowed)
  sine_mode           ///< contact wire w = A sin(k pi x / L), at rest (no constraints)
};

/**
 * A scene: which bodies exist and which effects act (issue 7). The defaults
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
  PantographType pantograph = PantographType::two_mass;
  Constraint::Kind contact = Constraint::Kind::unilateral;
  double moving_force = 100.; ///< [N], upwards, for PantographType::moving_force
  InitialShape initial_shape = InitialShape::static_equilibrium;
  unsigned int initial_mode = 1;   ///< k of the sine mode
  double initial_amplitude = 0.01; ///< A of the sine mode [m]

  /// True for the two lumped-mass models: a pantograph body in contact with the wire.
  bool has_pantograph_body() const
  {
    return pantograph == PantographType::two_mass ||
           pantograph == PantographType::three_mass;
  }
  bool has_droppers() const { return droppers != DropperModel::absent; }
  /**
   * The classical moving-load problem: a moving force on the elastic contact
   * wire alone (no droppers), no gravity, no damping, from rest. Its series
   * solution (MovingLoadSeries) is the exact reference.
   */
  bool is_classical_moving_load() const
  {
    return pantograph == PantographType::moving_force && !has_droppers() && !gravity &&
           !damping && initial_shape == InitialShape::rest &&
           contact_wire == WireModel::elastic;
  }

  static void declare_parameters(dealii::ParameterHandler& prm);
  void parse_parameters(dealii::ParameterHandler& prm);
  /// Cross-checks (a wire without stiffness, a moving force on a rigid wire, ...);
  /// throws InputError naming the parameter.
  void check() const;
};

const char* to_string(PantographType type);
} // namespace pantocat
