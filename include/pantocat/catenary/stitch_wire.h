#pragma once

#include <deal.II/base/parameter_handler.h>

#include <climits>
#include <vector>

namespace pantocat
{
/**
 * A stitch wire of a stitched catenary (doc/catenaries.md, "The stitched
 * catenary"): a tensioned string centred on a support of the section and
 * clamped to the carrier (the messenger) at both ends, x_s - length/2 and
 * x_s + length/2, where its vertical motion is the carrier's. The droppers
 * listed in `droppers` hang from it instead of from the carrier. In the
 * wave equation (2) it is a string: rho A w_tt + beta w_t - T w_xx = -rho A g
 * on its length, with no bending stiffness.
 */
struct StitchWire
{
  unsigned int support = 0;    ///< k of its support (0 = the section's start)
  double centre = 0.;          ///< x_s [m]: the position of that support
  double length = 0.;          ///< [m]; clamps at centre -+ length / 2
  double mass_per_length = 0.; ///< rho A [kg/m]
  double tension = 0.;         ///< T [N]
  double damping = 0.;         ///< viscous beta [N s/m^2]
  double clamp_mass = 0.;      ///< [kg] of each of its two clamps, on the carrier
  /// The section's droppers (0-based) that hang from it, increasing.
  std::vector<unsigned int> droppers;

  double start() const { return centre - 0.5 * length; } ///< the first clamp [m]
  double end() const { return centre + 0.5 * length; }   ///< the second clamp [m]
};

/**
 * The entries of subsection Catenary/Stitch wire as given: the supports
 * that carry a stitch wire and its data, each one value for all of them or
 * one value per support (CatenaryParameters::place_stitch_wires() makes the
 * StitchWire list and refuses what does not fit the section).
 */
struct StitchWireEntries
{
  std::vector<unsigned int> supports; ///< empty: every support between spans
  std::vector<double> lengths{0.};    ///< 0: no stitch wire
  std::vector<double> tensions{2800.};
  std::vector<double> masses_per_length{0.31};
  std::vector<double> dampings{0.};
  std::vector<double> clamp_masses{0.1};
  /// Positions [m] from the support of the droppers that hang from it: one
  /// list for every stitched support or one per support; an empty list:
  /// every dropper strictly inside its length.
  std::vector<std::vector<double>> dropper_positions{{}};

  /// Declares the entries in the current subsection (Catenary/Stitch wire).
  static void declare_parameters(dealii::ParameterHandler& prm);
  /// Reads them from the current subsection.
  void parse_parameters(dealii::ParameterHandler& prm);
};

/// CatenaryParameters::dropper_stitch_wire of a dropper hanging from the carrier.
constexpr unsigned int no_stitch_wire = UINT_MAX;
} // namespace pantocat
