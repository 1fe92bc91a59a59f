#pragma once

#include <optional>
#include <string>
#include <vector>

namespace pantocat
{
/// What `pantocat-fem` was asked to do on its command line.
struct CommandLine
{
  bool help = false;
  std::optional<std::string> print_parameters; ///< "prm" | "json"
  std::string parameter_file;
  std::vector<std::string> overrides; ///< --set "Subsection/Name=value", in order
  std::optional<std::string> output_directory;

  /// Parses argv; throws InputError on unknown options or missing values.
  static CommandLine parse(int argc, const char* const* argv);

  static std::string usage();
};
} // namespace pantocat
