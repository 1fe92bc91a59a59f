#pragma once

#include <deal.II/base/parameter_handler.h>

#include <exception>
#include <string>
#include <vector>

namespace pantocat
{
/**
 * Reads the prm file @p file into @p prm (whose entries are declared), then
 * applies the command-line overrides, each "Subsection/.../Name=value".
 * Every error becomes an InputError with one line: deal.II's own message
 * (file, line, entry, allowed pattern) without its stack trace.
 */
void read_parameter_file(dealii::ParameterHandler& prm, const std::string& file,
                         const std::vector<std::string>& overrides,
                         bool skip_undefined = false);

/// Applies one override "Subsection/.../Name=value"; throws InputError.
/// With @p skip_undefined, an entry that is not declared is ignored (a first pass).
void apply_parameter_override(dealii::ParameterHandler& prm, const std::string& setting,
                              bool skip_undefined = false);

/// The informative part of an exception's message, on one line.
std::string one_line_message(const std::exception& e);
} // namespace pantocat
