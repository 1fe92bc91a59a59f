#pragma once

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

struct DiscretisationParameters
{
  SpaceMethod method = SpaceMethod::fem;
  CarrierElement carrier_element = CarrierElement::linear_lagrange;
  unsigned int n_intervals = 500; ///< N + 1: cells of the equidistant grid
  LoadShape load_shape = LoadShape::smoothed_delta;
  double load_half_width = 0.2; ///< epsilon [m]

  static void declare_parameters(dealii::ParameterHandler& prm);
  void parse_parameters(dealii::ParameterHandler& prm);
  /// Checks against the span; throws InputError.
  void check(double span) const;
};
} // namespace pantocat
