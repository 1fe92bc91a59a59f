#pragma once

#include <pantocat/app/program_parameters.h>

#include <deal.II/base/parameter_handler.h>

#include <map>
#include <ostream>
#include <string>

namespace pantocat
{
/// The entries of @p prm as "Subsection/.../Name" -> value.
std::map<std::string, std::string> entries_of(const dealii::ParameterHandler& prm);

/**
 * "did you mean Catenary/Span?": the declared names of @p prm (entries, or
 * with @p subsection the subsections) nearest to the unknown @p name, up to
 * three paths, when one is within a few edits (case ignored); "" otherwise.
 */
std::string did_you_mean(const dealii::ParameterHandler& prm, const std::string& name,
                         bool subsection);

/**
 * The entries of @p prm whose values differ from the declared defaults, as
 * "Subsection/.../Name" -> value: what the case file (and the command line)
 * set. @p defaults holds the same declarations, unread.
 */
std::map<std::string, std::string> entries_set(const dealii::ParameterHandler& prm,
                                               const dealii::ParameterHandler& defaults);

/**
 * Warns on @p err (lines "pantocat-fem: warning: ...") about entries that the
 * run reads but does not use: a pantograph model's subsection filled for a
 * model the scene does not use, and Pantograph/Initial contact force or
 * Initial offset under Run/Start = static equilibrium (the start takes the
 * contact force from the pantograph). @p set is entries_set().
 */
void warn_about_unused_entries(const std::map<std::string, std::string>& set,
                               const ProgramParameters& parameters, std::ostream& err);
} // namespace pantocat
