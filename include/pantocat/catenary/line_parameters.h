#pragma once

#include <pantocat/catenary/catenary_parameters.h>

#include <deal.II/base/parameter_handler.h>

#include <utility>
#include <vector>

namespace pantocat
{
/**
 * A line of tension sections (subsection Line): n sections, each with the
 * data of subsection Catenary, consecutive ones joined by an overlap of o
 * spans in which both run side by side on shared supports O_0 .. O_o.
 *
 * In an overlap the outgoing section's contact wire stays at working height
 * and rises to its anchor: its support heights are Line/Overlap heights
 * H_0 .. H_o at O_0 .. O_o, and its target heights at the droppers follow
 * the straight lines through (O_i, H_i) and through z = 0 at the overlap's
 * middle. The incoming section's contact wire mirrors it (H_o at its anchor
 * O_0). Outside the overlaps, the section's own targets (its pre-sag, or its
 * target heights). The messenger is l_c above its contact wire at every
 * support. The sections, the wires and the pantographs are vertical only:
 * the stagger and the wires' lateral positions are not modelled.
 */
struct LineParameters
{
  unsigned int n_sections = 1;    ///< Line/Number of sections
  unsigned int overlap_spans = 3; ///< o: Line/Overlap spans
  /// H_0 .. H_o [m] of the outgoing contact wire at the overlap's supports.
  std::vector<double> overlap_heights = {0., 0., 0.2, 0.5};

  bool is_line() const { return n_sections > 1; }

  /**
   * The sections along the line. For one, @p section as it is. For several,
   * copies of it named "section k", each starting at the first support of
   * its predecessor's overlap, with the overlaps' support heights and target
   * heights (pre-sag 0 in overlap spans).
   */
  std::vector<CatenaryParameters> sections(const CatenaryParameters& section) const;
  /// The overlaps [x0, x1] along the line: from O_0 to O_o of each (n - 1).
  std::vector<std::pair<double, double>>
  overlaps(const CatenaryParameters& section) const;
  /// The line's length [m]: from the first section's start to the last one's end.
  double length(const CatenaryParameters& section) const;

  static void declare_parameters(dealii::ParameterHandler& prm);
  void parse_parameters(dealii::ParameterHandler& prm);
  /**
   * Refuses (InputError naming the Line entry) an overlap shorter than one
   * span, one whose supports do not coincide (the last o spans of a section
   * differ from its first o), one so long that a section's anchor lies
   * inside a third section, and overlap heights not one per overlap support.
   */
  void check(const CatenaryParameters& section) const;

private:
  /// The outgoing contact wire's height at @p xi [m] from the overlap's first support.
  double outgoing_height(const std::vector<double>& overlap_supports, double xi) const;
};
} // namespace pantocat
