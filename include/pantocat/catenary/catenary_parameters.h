#pragma once

#include <pantocat/catenary/stitch_wire.h>

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <utility>
#include <vector>

namespace pantocat
{
/// Physical data of one wire of the catenary, Eq. (2).
struct WireParameters
{
  double mass_per_length = 0.;   ///< rho A [kg/m]
  double tension = 0.;           ///< T [N]
  double bending_stiffness = 0.; ///< E I [N m^2]; 0 for the string (carrier)
  double damping = 0.;           ///< beta [N s/m^2]

  /// Wave speed sqrt(T / rho A) [m/s].
  double wave_speed() const;
};

/// How the droppers' lengths are obtained.
enum class DropperDesign
{
  given,   ///< Catenary/Droppers/Lengths as given (the paper's 0.95 m)
  designed ///< form-finding: the static contact wire on its target at every dropper
};

/// Where the pre-sag parabola of a span is zero (Catenary/Droppers/Pre-sag reference).
enum class PresagReference
{
  supports,              ///< at the span's supports (x from its first support)
  first_and_last_dropper ///< at the span's first and last dropper (the circulated data)
};

/// How the carrier is held at the supports between spans.
enum class CarrierSupport
{
  fixed, ///< w_c = l_c there (a bilateral constraint)
  spring ///< a vertical spring, preloaded so that w_c = l_c in the static state
};

/// The damping of the catenary's wires.
enum class CatenaryDamping
{
  viscous, ///< beta w_t of each wire, Eq. (2)
  rayleigh ///< C = alpha M + beta K of the catenary (without droppers and pantographs)
};

/**
 * A tension section of the catenary: n spans end to end, a carrier and a
 * contact wire over all of them, both pinned at the section's ends (x = 0 and
 * x = length()), connected by droppers in every span (Eqs. (2)-(6)); at each
 * support between spans the carrier is held (fixed or by a spring) and the
 * contact wire by a steady arm (a vertical spring with a lumped mass).
 *
 * One span (the default) is the paper's reduced model of Sec. 2.2 / Fig. 4;
 * the defaults are its benchmark data (catenary Re 250).
 *
 * A stitched catenary adds stitch wires at supports (StitchWire): the
 * droppers near such a support hang from its stitch wire, which is clamped to
 * the carrier.
 *
 * Heights: the carrier at l_c (the encumbrance, Catenary/Encumbrance) and
 * the contact wire at 0 at every support; a dropper j of length l_j joins the
 * carrier at height w_c to the contact wire at w_w = w_c - l_j when taut.
 */
struct CatenaryParameters
{
  /**
   * The section's name in a line of several ("section k"), prefixed to its
   * bodies and constraints; empty for a case of one section.
   */
  std::string name;
  /// x [m] along the line of the section's first support (its x = 0).
  double start = 0.;
  /**
   * Heights [m] of the contact wire at every support (n + 1, z = 0 the working
   * height), the messenger l_c above them; between supports both wires'
   * reference is the straight chord (support_chord()), so that a dropper sees
   * the same height at both ends. Empty: 0 at every support.
   */
  std::vector<double> support_heights;
  double span = 20.0; ///< L [m]: the length of each span (Catenary/Span)
  /// Span lengths [m] of the section, first to last (empty: n_spans x span).
  std::vector<double> span_lengths;
  unsigned int n_spans = 1; ///< number of spans when span_lengths is empty
  double support_height =
      1.0; ///< l_c: encumbrance, carrier height at the supports [m], Eq. (3)
  double gravity = 9.81; ///< g [m/s^2]
  WireParameters carrier = {0.6, 15000., 0., 0.03};
  WireParameters contact_wire = {1.068, 15000., 150., 0.03};

  /// x_{d,j} [m] of every dropper of the section, measured from x = 0, increasing.
  std::vector<double> dropper_positions = {5.5, 14.5};
  /// l_j [m] of every dropper (given, or from the design: DropperDesign).
  std::vector<double> dropper_lengths = {0.95, 0.95};
  /// The span (0-based) of every dropper.
  std::vector<unsigned int> dropper_spans = {0, 0};
  double dropper_mass_per_length = 0.14; ///< rho_d A_d [kg/m]
  double clamp_mass = 0.25;              ///< m_s [kg] of a clamp on the carrier
  double contact_wire_clamp_mass = 0.25; ///< m_s [kg] of a clamp on the contact wire
  double dropper_stiffness = 1e5;        ///< k_d [N/m] of an elastic dropper in tension

  DropperDesign design = DropperDesign::given;
  /**
   * Pre-sag s [m] of the contact wire, for the design: at the dropper points
   * the static contact wire lies on z = -4 s xi (1 - xi), zero at the two
   * ends of its reference (presag_reference): xi = (x - x_0)/(x_1 - x_0) with
   * x_0, x_1 the span's supports or its first and last dropper
   * (doc/catenaries.md, "The static design").
   */
  double presag = 0.;
  PresagReference presag_reference = PresagReference::supports;
  /**
   * A target a dropper could hold only by pushing: false, the design refuses
   * it; true, the design leaves that dropper at zero force and the wire where
   * its neighbours put it (Catenary/Droppers/Unreachable targets).
   */
  bool release_unreachable_targets = false;
  /**
   * Target heights z_j [m] of the static contact wire at every dropper of the
   * section (z = 0 at the steady arms, negative below), for the design; they
   * replace the pre-sag. Empty: the pre-sag's (dropper_target_heights()).
   */
  std::vector<double> target_heights;

  /// Point masses (clamps, half droppers, steady arms) in the mass matrix too,
  /// not only as loads (the paper: loads only, Eq. (4)).
  bool point_mass_inertia = false;

  CarrierSupport carrier_support = CarrierSupport::fixed;
  double carrier_support_stiffness = 5e5; ///< [N/m], CarrierSupport::spring
  double steady_arm_stiffness = 0.;       ///< [N/m]; 0: no steady arms
  double steady_arm_mass = 0.;            ///< [kg], lumped on the contact wire
  /// Support numbers k (0 = section start .. n = section end) with a steady
  /// arm, increasing, all in 1..n-1; empty: every support between spans.
  std::vector<unsigned int> steady_arm_supports;
  /**
   * Static forces [N] (upward > 0) of the springs at the interior supports in
   * the designed static state: carrier supports (CarrierSupport::spring) and
   * steady arms. Set by the design (design_catenary()); empty: 0.
   */
  std::vector<double> carrier_support_preloads, steady_arm_preloads;

  /// The stitch wires (Catenary/Stitch wire), by increasing support; none with
  /// a length of 0. Empty: a simple catenary.
  std::vector<StitchWire> stitch_wires;
  /// For every dropper, the index of the stitch wire it hangs from, or
  /// no_stitch_wire (it hangs from the carrier); empty: every one from the carrier.
  std::vector<unsigned int> dropper_stitch_wire;

  CatenaryDamping damping = CatenaryDamping::viscous;
  double rayleigh_alpha = 0.; ///< [1/s]
  double rayleigh_beta = 0.;  ///< [s]

  unsigned int n_droppers() const { return dropper_positions.size(); }
  /// The stitch wire dropper @p j hangs from, or no_stitch_wire (the carrier).
  unsigned int stitch_wire_of(const unsigned int j) const
  {
    return j < dropper_stitch_wire.size() ? dropper_stitch_wire[j] : no_stitch_wire;
  }
  /// The spans' lengths, first to last.
  std::vector<double> spans() const;
  unsigned int number_of_spans() const { return spans().size(); }

  /**
   * The wires' domain is [0, length()]: the spans of the section end to end.
   * Grids, positions and bounds refer to the domain.
   */
  double length() const;
  /// Positions of the supports along the domain: the ends of every span (n + 1).
  std::vector<double> support_positions() const;
  /// The supports between spans, where steady arms and carrier supports sit.
  std::vector<double> interior_supports() const;
  /// Positions of the steady arms (Supports/Steady arm supports), increasing.
  std::vector<double> steady_arm_positions() const;

  /**
   * The target height z_j [m] of the static contact wire at every dropper, the
   * heights the design (Design = designed) puts it on: target_heights when
   * given, else the pre-sag parabola of each span in its presag_reference. In
   * O(n) for all of them.
   */
  std::vector<double> dropper_target_heights() const;
  /**
   * What the design holds the contact wire at: the target heights less the
   * support chord at every dropper, the displacement from the chord.
   */
  std::vector<double> dropper_target_displacements() const;

  /**
   * The contact wire's reference height h(x) [m] at the section's @p x (the
   * straight chord between the support heights; beyond an anchor that
   * anchor's height), or its slope h'(x) for @p derivative = 1.
   */
  double support_chord(double x, unsigned int derivative = 0) const;
  /// The changes of slope of the chord at every support (n + 1; an anchor's
  /// against the level continuation beyond it).
  std::vector<double> support_chord_kinks() const;

  /// Gravity load of a clamp and half a dropper at dropper j, (m_s + l_j rho_d A_d / 2)
  /// g, Eq. (4), on the wire it hangs from (@p carrier_side: the carrier or its
  /// stitch wire) or the contact wire.
  double clamp_load(unsigned int j, bool carrier_side = true) const;
  /// Mass of a clamp and half a dropper at dropper j on the carrier or the contact wire.
  double point_mass(unsigned int j, bool carrier_side) const;
  /// Mass of half a dropper of @p length, l rho_d A_d / 2: what each wire
  /// carries of it at its clamp, Eq. (4).
  double half_dropper_mass(const double length) const
  {
    return 0.5 * length * dropper_mass_per_length;
  }

  static void declare_parameters(dealii::ParameterHandler& prm);
  void parse_parameters(dealii::ParameterHandler& prm);

  /// The old name of subsection Catenary/Messenger: declared and read, never printed.
  static constexpr const char* old_messenger_subsection = "Carrier";
  /**
   * Moves what a file or --set gave under the old subsection name
   * Catenary/Carrier to Catenary/Messenger (resetting the old entries), with
   * one warning on @p warnings; an entry given under both names is refused.
   */
  static void move_old_names(dealii::ParameterHandler& prm, std::ostream& warnings);
  /// Cross-checks; throws InputError naming the parameter.
  void check() const;

  /**
   * The stitch wires from the entries @p given (after the droppers are
   * placed); refuses a support that is not between spans, a stitch wire
   * clamped outside the section, longer than its spans allow or reaching
   * into its neighbour's, and dropper positions outside it or where the
   * section has no dropper (InputError naming the Catenary/Stitch wire entry).
   */
  void place_stitch_wires(const StitchWireEntries& given);
  /// Stitch wires inside their spans with their data and droppers
  /// (check() for a catenary not read from a file).
  void check_stitch_wires() const;

private:
  /// Spring supports with a stiffness; steady arms only between spans, in
  /// increasing order (section ends are anchors), and only with a stiffness.
  void check_supports() const;
  /// Target heights one per dropper, not together with a pre-sag; a pre-sag
  /// zero at the first and last dropper only in spans with two droppers or more.
  void check_targets() const;
  /// Where each span's pre-sag parabola is zero: x_0 and x_1 - x_0 of every span.
  std::vector<std::pair<double, double>> presag_chords() const;
  /// The section's target heights from the @p given ones, one per dropper of a
  /// span (when @p one_list of positions serves every span) or of the section.
  void place_target_heights(const std::vector<double>& given, bool one_list);
  /// The section's droppers from the per-span @p positions and the @p lengths given.
  void place_droppers(const std::vector<std::vector<double>>& positions,
                      const std::vector<double>& lengths);
};
} // namespace pantocat
