#pragma once

#include <pantocat/app/parameter_input.h>
#include <pantocat/app/program_parameters.h>

#include <filesystem>
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

/// The shipped case prm/catenary/@p name with the --set @p overrides, read from
/// the repository root (the working directory its includes are relative to).
inline ProgramParameters shipped_catenary(const std::string& name,
                                          const std::vector<std::string>& overrides = {})
{
  std::filesystem::current_path(PANTOCAT_SOURCE_DIR);
  return read_case(source_file("prm/catenary/" + name), overrides);
}
#endif
} // namespace pantocat
