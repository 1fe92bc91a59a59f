#include <pantocat/app/parameter_input.h>
#include <pantocat/base/input_error.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <fstream>
#include <sstream>

namespace pantocat
{
namespace
{
std::string collapse_whitespace(const std::string& text)
{
  std::istringstream in(text);
  std::string word, out;
  while (in >> word)
    out += (out.empty() ? "" : " ") + word;
  return out;
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

void apply_parameter_override(dealii::ParameterHandler& prm, const std::string& setting,
                              const bool skip_undefined)
{
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
    throw InputError("--set " + setting + ": " + message);
  }
}

void read_parameter_file(dealii::ParameterHandler& prm, const std::string& file,
                         const std::vector<std::string>& overrides,
                         const bool skip_undefined)
{
  std::ifstream in(file);
  if (!in)
    throw InputError("cannot read parameter file '" + file +
                     "'; write a template with: pantocat-fem --print-parameters > " +
                     file);
  try
  {
    prm.parse_input(in, file, "", skip_undefined);
  }
  catch (const std::exception& e)
  {
    throw InputError(one_line_message(e));
  }
  for (const auto& setting : overrides)
    apply_parameter_override(prm, setting, skip_undefined);
}
} // namespace pantocat
