#pragma once

#include <pantocat/base/physical_memory.h>

#include <deal.II/base/parameter_handler.h>

namespace pantocat
{
/// Space discretisation of Sec. 4: finite elements (4.2) or finite differences (4.3).
enum class SpaceMethod
{
  fem,
  fdm
};

/// How the contact force is distributed along the wire (Sec. 4.1).
enum class LoadShape
{
  smoothed_delta, ///< delta_eps, the cubic C1 spline of (25)
  point           ///< a Dirac point load as in (15)/(16)
};

const char* to_string(SpaceMethod method);
SpaceMethod space_method_from_string(const std::string& name);

/// FEM element of the carrier: the paper's string (C0) or a beam (C1).
enum class CarrierElement
{
  linear_lagrange, ///< Sec. 4.2: the carrier is a string
  cubic_hermite    ///< as the contact wire: for a carrier with bending stiffness
};

/**
 * Memory [bytes] a run needs per interval of the grid, above the program's
 * fixed 0.2 GB: an upper bound of what was measured (peak resident memory at
 * N+1 = 5000 and 50000, FEM and FDM): IDA 18.6 kB (its sparse Jacobian and
 * the Newton matrices), BDF-2 and the static solve 4 kB, the explicit
 * methods 2.4 kB.
 */
constexpr double memory_per_interval = 32e3;

/// The memory a run on @p n_intervals intervals needs, by memory_per_interval.
double estimated_memory_bytes(unsigned int n_intervals);

struct DiscretisationParameters
{
  SpaceMethod method = SpaceMethod::fem;
  CarrierElement carrier_element = CarrierElement::linear_lagrange;
  unsigned int n_intervals = 500; ///< N + 1: cells of the equidistant grid
  LoadShape load_shape = LoadShape::smoothed_delta;
  double load_half_width = 0.2; ///< epsilon [m]

  static void declare_parameters(dealii::ParameterHandler& prm);
  void parse_parameters(dealii::ParameterHandler& prm);
  /**
   * Checks against the span, and that a run on this grid fits into the
   * machine's physical memory (estimated_memory_bytes()): a grid that does
   * not is refused here, naming the estimate, instead of ending in an
   * allocation failure; throws InputError.
   */
  void check(double span) const;
  /// The memory part of check().
  void check_memory() const;
};
} // namespace pantocat
