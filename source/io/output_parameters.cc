#include <pantocat/io/output_parameters.h>

namespace pantocat
{
void OutputParameters::declare_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Output");
  prm.declare_entry("Output directory", "output", dealii::Patterns::FileName(),
                    "Directory for all results; created if needed. The resolved "
                    "parameters are written to parameters.prm inside it.");
  prm.declare_entry("VTU subdivisions", "4", dealii::Patterns::Integer(1, 64),
                    "Sample points per cell in VTU files (shows the cubic Hermite "
                    "shape between vertices).");
  prm.leave_subsection();
}

void OutputParameters::parse_parameters(dealii::ParameterHandler& prm)
{
  prm.enter_subsection("Output");
  directory        = prm.get("Output directory");
  vtu_subdivisions = prm.get_integer("VTU subdivisions");
  prm.leave_subsection();
}
} // namespace pantocat
