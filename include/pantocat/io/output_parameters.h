#pragma once

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace pantocat
{
struct OutputParameters
{
  std::string directory = "output";      ///< created if needed
  unsigned int vtu_subdivisions = 4;     ///< sample points per cell in VTU files
  unsigned int time_series_interval = 1; ///< write every k-th time point
  bool plots = true;                     ///< PNG plots with gnuplot, if installed

  static void declare_parameters(dealii::ParameterHandler& prm);
  void parse_parameters(dealii::ParameterHandler& prm);
};
} // namespace pantocat
