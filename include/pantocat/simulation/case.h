#pragma once

#include <pantocat/catenary/catenary_parameters.h>
#include <pantocat/catenary/line_parameters.h>
#include <pantocat/scene/scene_parameters.h>
#include <pantocat/simulation/guard_parameters.h>
#include <pantocat/space/discretisation_parameters.h>
#include <pantocat/time/time_integration_parameters.h>

#include <vector>

namespace pantocat
{
/**
 * Deviations of an installed catenary from its design (Mode = monte carlo):
 * what the fitters got wrong, applied by the CaseRunner after the static
 * design (the droppers were cut for the design, then installed with these
 * errors). Empty lists and factors of 1: the catenary as designed.
 */
struct InstallationDeviations
{
  /// Added to each dropper's length l_j [m], in dropper order (empty: none).
  std::vector<double> dropper_lengths;
  /**
   * Height error [m] of each steady arm's fixing, in the order of
   * CatenaryParameters::steady_arm_positions() (empty: none): an arm fixed
   * delta higher pulls with k_s delta more (its preload grows by that).
   */
  std::vector<double> steady_arm_heights;
  double carrier_tension_factor = 1.;      ///< T_c = factor x the design's tension
  double contact_wire_tension_factor = 1.; ///< T_w = factor x the design's tension

  /// True if any deviation is set.
  bool any() const;
  /**
   * Applies the deviations to the designed (or given) catenary @p c. Throws
   * InputError when the installed catenary is one a prm file could not give
   * (CatenaryParameters::check(): a dropper of length <= 0, a tension <= 0).
   */
  void apply(CatenaryParameters& c) const;
};

/**
 * A case: the physics and the numerics of one simulation, and nothing of how
 * it was asked for (no command line, no output settings). The scene says
 * which bodies and effects exist (any number of pantographs), the catenary
 * the wires' domain and the geometry along it, the discretisation and time
 * integration how it is solved, the guards when a run is stopped. Built once
 * from the parameters; every mode and every study runs a case through the
 * CaseRunner.
 */
struct Case
{
  SceneParameters scene;
  CatenaryParameters catenary;
  DiscretisationParameters discretisation;
  TimeIntegrationParameters time_integration;
  GuardParameters guards;
  /// Installation errors applied after the design (Monte Carlo); none by default.
  InstallationDeviations installation = {};
  /// The line: catenary's section once, or several joined by overlaps.
  LineParameters line = {};

  /// The tension sections along the line (LineParameters::sections()).
  std::vector<CatenaryParameters> sections() const { return line.sections(catenary); }
  /**
   * The supports along the line of section @p section (1-based; the section
   * itself for a single one), for Statistics/Window section; throws
   * InputError naming it if there is no such section.
   */
  std::vector<double> window_supports(unsigned int section) const;
  /// The length [m] of the line: the wires' domain along which the pantographs run.
  double line_length() const { return line.length(catenary); }

  /**
   * The end time t_e of a dynamic run: the first pantograph (moving force or
   * body) to reach its final position ends it (PantographParameters::end_time(),
   * with its speed ramp); without any, pantograph 1's.
   */
  double end_time() const;

  /**
   * Cross-checks between the parts (bending of the carrier and its element,
   * every pantograph inside the domain for the whole run, ...); throws
   * InputError naming the parameter, the value and what is allowed.
   */
  void check() const;
  /// What a line of several sections refuses (a moving force, rigid wires, installation
  /// deviations).
  void check_line() const;
  /// A speed ramp of 0 or at least one time step; throws InputError naming it.
  void check_speed_ramp(const PantographParameters& p) const;
  /// A penalty contact's damping within k_c t_e; throws InputError naming @p parameter.
  void check_contact_damping(const Compliance& law, const std::string& parameter) const;

  /**
   * What a dynamic run needs beyond check(): unknowns to integrate, and a
   * number of steps up to end_time() that is finite and fits into memory.
   */
  void check_dynamics() const;
};
} // namespace pantocat
