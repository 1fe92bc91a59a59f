#pragma once

#include <deal.II/base/parameter_handler.h>

#include <boost/property_tree/ptree.hpp>

#include <exception>
#include <string>
#include <vector>

namespace pantocat
{
/**
 * Reads the prm file @p file into @p prm (whose entries are declared), then
 * applies the command-line overrides, each "Subsection/.../Name=value", and
 * checks every value against its pattern that deal.II lets through (one with
 * a '{').
 * Every error becomes an InputError with one line: deal.II's own message
 * (file, line, entry, allowed pattern) without its stack trace.
 */
void read_parameter_file(dealii::ParameterHandler& prm, const std::string& file,
                         const std::vector<std::string>& overrides,
                         bool skip_undefined = false);

/**
 * Applies one override "Subsection/.../Name=value"; throws InputError, also
 * for a setting with a control character (a newline would inject prm lines).
 * With @p skip_undefined, an entry that is not declared is ignored (a first pass).
 */
void apply_parameter_override(dealii::ParameterHandler& prm, const std::string& setting,
                              bool skip_undefined = false);

/**
 * Checks, before deal.II reads it, that @p file and every file it includes
 * (`include name`, relative to the working directory, as deal.II resolves it)
 * is a regular file, and that the includes form no cycle (a file including
 * itself, directly or through others); throws an InputError naming the file,
 * the line and the include.
 */
void check_parameter_file(const std::string& file);

/**
 * @p prm printed in @p style (PRM or JSON) without the subsections that are
 * only read under an old name (Catenary/Carrier, now Catenary/Messenger):
 * what --print-parameters and a run's parameters.prm show.
 */
std::string printed_parameters(const dealii::ParameterHandler& prm,
                               dealii::ParameterHandler::OutputStyle style);

/**
 * Every declared entry of @p prm as a tree, read from its JSON form: per
 * entry "value", "default_value", "documentation", "pattern_description".
 * The JSON reader wants UTF-8, so bytes above 0x7f are read as '?'.
 */
boost::property_tree::ptree parameter_tree(const dealii::ParameterHandler& prm);

/// The informative part of an exception's message, on one line.
std::string one_line_message(const std::exception& e);

/// @p text with every control character (newline included) written as \xNN.
std::string printable_line(const std::string& text);
} // namespace pantocat
