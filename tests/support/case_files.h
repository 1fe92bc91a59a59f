#pragma once

#include <pantocat/app/parameter_input.h>
#include <pantocat/app/program_parameters.h>

#include <string>
#include <vector>

namespace pantocat
{
/// The parameters of the prm @p file with the --set @p overrides, read as the program
/// reads them.
inline ProgramParameters read_case(const std::string& file,
                                   const std::vector<std::string>& overrides = {})
{
  dealii::ParameterHandler prm;
  read_program_parameters(prm, file, overrides);
  ProgramParameters p;
  p.parse_parameters(prm);
  return p;
}

#ifdef PANTOCAT_SOURCE_DIR
/// A file of the source tree, e.g. source_file("prm/benchmark-32.prm").
inline std::string source_file(const std::string& relative)
{
  return std::string(PANTOCAT_SOURCE_DIR) + "/" + relative;
}
#endif
} // namespace pantocat
