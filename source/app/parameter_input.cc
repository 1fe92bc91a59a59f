#include <pantocat/app/input_warnings.h>
#include <pantocat/app/parameter_input.h>
#include <pantocat/base/input_error.h>
#include <pantocat/base/safe_files.h>
#include <pantocat/catenary/catenary_parameters.h>

#include <nlohmann/json.hpp>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/patterns.h>
#include <deal.II/base/utilities.h>

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace pantocat
{
namespace
{
/// At most this many include lines are followed in one parameter file and the
/// files it includes (a file that includes another twice, which includes a
/// third twice, ... would otherwise be read 2^depth times).
constexpr unsigned int max_includes = 1000;

/// A parameter file is a few kilobytes; one larger than this is no parameter file.
constexpr std::uint64_t max_parameter_file_bytes = std::uint64_t(16) << 20;

std::string collapse_whitespace(const std::string& text)
{
  std::istringstream in(text);
  std::string word, out;
  while (in >> word)
    out += (out.empty() ? "" : " ") + word;
  return out;
}

bool is_control_character(const char c)
{
  return static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
}

/// "Line <n> of file <name>: ", as deal.II starts its messages about a line.
std::string at_line(const std::string& file, const unsigned int line)
{
  return "Line <" + std::to_string(line) + "> of file <" + file + ">: ";
}

/**
 * Refuses a parameter file that cannot be read as one: missing, a directory
 * (an input stream opens one and reads it as empty, which would run the
 * defaults), or not a regular file (a FIFO or device may never end).
 * @p where starts the message.
 */
void require_regular_file(const std::string& file, const std::string& where)
{
  std::error_code error;
  const auto status = std::filesystem::status(file, error);
  if (status.type() == std::filesystem::file_type::not_found)
    throw InputError(where + "no such file");
  if (status.type() == std::filesystem::file_type::directory)
    throw InputError(where + "this is a directory, not a parameter file");
  if (error || status.type() != std::filesystem::file_type::regular)
    throw InputError(where + "not a regular file that can be read");
}

/**
 * The file named by an include line, or empty if @p line is none. Lines are
 * read as deal.II's ParameterHandler reads them: a comment from '#' on is
 * dropped, tabs count as spaces, and "include " or "INCLUDE " starts the
 * statement; the name is relative to the working directory.
 */
std::string included_file(std::string line)
{
  line = line.substr(0, line.find('#'));
  std::replace(line.begin(), line.end(), '\t', ' ');
  line = dealii::Utilities::trim(line);
  if (!dealii::Utilities::match_at_string_start(line, "include ") &&
      !dealii::Utilities::match_at_string_start(line, "INCLUDE "))
    return "";
  return dealii::Utilities::trim(line.substr(7));
}

/// The logical lines of @p file with their first physical line number: lines
/// ending in a backslash continue on the next one (as deal.II joins them).
std::vector<std::pair<unsigned int, std::string>> logical_lines(const std::string& file)
{
  std::ifstream in(file);
  std::vector<std::pair<unsigned int, std::string>> lines;
  std::string line, joined;
  unsigned int number = 0, first = 0;
  bool continued = false;
  while (std::getline(in, line))
  {
    ++number;
    if (!continued)
      first = number, joined.clear();
    line = dealii::Utilities::trim(line);
    continued = !line.empty() && line.back() == '\\';
    joined += continued ? line.substr(0, line.size() - 1) : line;
    if (!continued)
      lines.emplace_back(first, joined);
  }
  if (continued)
    lines.emplace_back(first, joined);
  return lines;
}

/**
 * Follows the include lines of @p file (already checked to be a regular
 * file) before deal.II reads it: each included file must be a regular file,
 * and no file may include itself, directly or through others (deal.II would
 * recurse until the stack overflows). @p chain holds the files being read,
 * outermost first.
 */
void check_includes(const std::string& file, std::vector<std::string>& chain,
                    unsigned int& includes)
{
  std::error_code error;
  const std::filesystem::path canonical = std::filesystem::canonical(file, error);
  chain.push_back(error ? file : canonical.string());
  for (const auto& [number, line] : logical_lines(file))
  {
    const std::string target = included_file(line);
    if (target.empty())
      continue;
    const std::string where = at_line(file, number) + "include " + target + ": ";
    require_regular_file(target, where);
    if (++includes > max_includes)
      throw InputError(where + "more than " + std::to_string(max_includes) +
                       " include lines in all; the includes repeat too often");
    const std::string resolved = std::filesystem::canonical(target, error).string();
    const auto cycle = std::find(chain.begin(), chain.end(), resolved);
    if (cycle != chain.end())
    {
      std::string path;
      for (auto f = cycle; f != chain.end(); ++f)
        path += *f + " -> ";
      throw InputError(where + "include cycle " + path + resolved +
                       " (a file must not include itself)");
    }
    check_includes(target, chain, includes);
  }
  chain.pop_back();
}

/**
 * Checks the values of the entries under @p node (the JSON form of the
 * parameters, at subsection @p path) whose value contains '{' against their
 * patterns. deal.II does not check those: '{' starts the alternatives of its
 * MultipleParameterLoop, which this program does not use; "{abc}" would
 * reach get_double(), and "{x}" for a selection would be taken as its last
 * choice. The message shows the value as @p prm holds it.
 */
void check_values_with_braces(const dealii::ParameterHandler& prm,
                              const boost::property_tree::ptree& node,
                              const std::vector<std::string>& path)
{
  for (const auto& [key, child] : node)
  {
    const auto value = child.get_optional<std::string>("value");
    const auto pattern = child.get_optional<std::string>("pattern_description");
    if (!value || !pattern)
    {
      std::vector<std::string> inner = path;
      inner.push_back(key);
      check_values_with_braces(prm, child, inner);
      continue;
    }
    if (value->find('{') == std::string::npos)
      continue;
    const auto matcher = dealii::Patterns::pattern_factory(*pattern);
    if (matcher && !matcher->match(*value))
    {
      std::string name;
      for (const auto& p : path)
        name += p + "/";
      throw InputError(name + key + " = " + prm.get(path, key) +
                       ": does not match the pattern " + *pattern);
    }
  }
}

/**
 * check_values_with_braces() for all of @p prm (parameter_tree(): a byte
 * above 0x7f, read as '?', is accepted by no pattern that refuses '{' either).
 */
void check_values_with_braces(const dealii::ParameterHandler& prm)
{
  check_values_with_braces(prm, parameter_tree(prm), {});
}
} // namespace

boost::property_tree::ptree parameter_tree(const dealii::ParameterHandler& prm)
{
  std::ostringstream printed;
  prm.print_parameters(printed, dealii::ParameterHandler::JSON);
  std::string json = printed.str();
  std::replace_if(
      json.begin(), json.end(),
      [](const char c) { return static_cast<unsigned char>(c) > 0x7f; }, '?');
  std::istringstream in(json);
  boost::property_tree::ptree tree;
  boost::property_tree::read_json(in, tree);
  return tree;
}

namespace
{
/// @p message with a suggestion for a misspelled entry or subsection, if any.
std::string with_suggestion(const dealii::ParameterHandler& prm,
                            const std::string& message)
{
  const std::vector<std::pair<std::string, bool>> unknowns = {
      {"No entry with name <", false},
      {"There is no such subsection to be entered: ", true}};
  for (const auto& [marker, subsection] : unknowns)
  {
    const std::size_t at = message.find(marker);
    if (at == std::string::npos)
      continue;
    const std::size_t first = at + marker.size();
    const std::size_t last = subsection ? message.size() : message.find('>', first);
    const std::string hint = did_you_mean(
        prm, dealii::Utilities::trim(message.substr(first, last - first)), subsection);
    if (hint.empty())
      return message;
    const bool stop = !message.empty() && message.back() == '.';
    return message.substr(0, message.size() - (stop ? 1 : 0)) + "; " + hint;
  }
  return message;
}
} // namespace

std::string one_line_message(const std::exception& e)
{
  if (const auto* d = dynamic_cast<const dealii::ExceptionBase*>(&e))
  {
    std::ostringstream info;
    d->print_info(info); // the "additional information" only, no stack trace
    const std::string text = collapse_whitespace(info.str());
    if (!text.empty())
      return text;
  }
  return collapse_whitespace(e.what());
}

std::string printable_line(const std::string& text)
{
  std::string out;
  for (const char c : text)
    if (is_control_character(c))
    {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", static_cast<unsigned char>(c));
      out += escaped;
    }
    else
      out += c;
  return out;
}

void apply_parameter_override(dealii::ParameterHandler& prm, const std::string& setting,
                              const bool skip_undefined)
{
  // A newline (or any control character) would start a line of its own in the
  // text below: --set "A/B=1\nend\nsubsection C\nset D = 2" would set C/D.
  const auto control = std::find_if(setting.begin(), setting.end(), is_control_character);
  if (control != setting.end())
    throw InputError("--set " + printable_line(setting) +
                     ": contains the control character " +
                     printable_line(std::string(1, *control)) +
                     "; a value must be printable text on one line");
  const auto eq = setting.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError("--set " + setting +
                     ": expected \"Subsection/.../Name=value\", e.g. "
                     "\"Discretisation/Method=fdm\"");
  const std::string path = setting.substr(0, eq), value = setting.substr(eq + 1);
  const std::vector<std::string> parts = dealii::Utilities::split_string_list(path, '/');
  std::string text;
  for (unsigned int i = 0; i + 1 < parts.size(); ++i)
    text += "subsection " + parts[i] + "\n";
  text += "set " + parts.back() + " = " + value + "\n";
  for (unsigned int i = 0; i + 1 < parts.size(); ++i)
    text += "end\n";
  try
  {
    prm.parse_input_from_string(text, "", skip_undefined);
  }
  catch (const std::exception& e)
  {
    // Drop deal.II's "Line <n> of file <input string>:": the line is ours.
    std::string message = one_line_message(e);
    const auto colon = message.find(">: ");
    if (message.rfind("Line <", 0) == 0 && colon != std::string::npos)
      message = message.substr(colon + 3);
    throw InputError("--set " + setting + ": " + with_suggestion(prm, message));
  }
}

std::string printed_parameters(const dealii::ParameterHandler& prm,
                               const dealii::ParameterHandler::OutputStyle style)
{
  std::ostringstream printed;
  prm.print_parameters(printed, style);
  const std::string old = CatenaryParameters::old_messenger_subsection;
  if (style & dealii::ParameterHandler::JSON)
  {
    nlohmann::ordered_json json = nlohmann::ordered_json::parse(printed.str());
    json["Catenary"].erase(old);
    return json.dump(2) + "\n";
  }
  // PRM: drop the lines from "  subsection Carrier" in Catenary to its "  end"
  // and the blank line after it.
  std::istringstream in(printed.str());
  std::string out, line, section;
  bool skipping = false, after = false;
  while (std::getline(in, line))
  {
    if (line.rfind("subsection ", 0) == 0)
      section = line.substr(11);
    if (!skipping && section == "Catenary" && line == "  subsection " + old)
      skipping = true;
    else if (skipping && line == "  end")
      skipping = false, after = true;
    else if (!skipping && !(after && line.empty()))
      out += line + "\n", after = false;
  }
  return out;
}

void check_parameter_file(const std::string& file)
{
  require_regular_file(file, "cannot read parameter file '" + file + "': ");
  std::vector<std::string> chain;
  unsigned int includes = 0;
  check_includes(file, chain, includes);
}

void read_parameter_file(dealii::ParameterHandler& prm, const std::string& file,
                         const std::vector<std::string>& overrides,
                         const bool skip_undefined)
{
  // Read at once: a FIFO or a device is refused without waiting on it.
  const FileContent content = read_regular_file(file, max_parameter_file_bytes, true);
  if (content.missing)
    throw InputError("cannot read parameter file '" + file +
                     "'; write a template with: pantocat-fem --print-parameters > " +
                     file);
  check_parameter_file(file);
  if (!content.bytes)
    throw InputError("cannot read parameter file '" + file + "': it " + content.problem);
  std::istringstream in(*content.bytes);
  try
  {
    prm.parse_input(in, file, "", skip_undefined);
  }
  catch (const std::exception& e)
  {
    throw InputError(with_suggestion(prm, one_line_message(e)));
  }
  for (const auto& setting : overrides)
    apply_parameter_override(prm, setting, skip_undefined);
  check_values_with_braces(prm);
}
} // namespace pantocat
