#include <pantocat/app/input_warnings.h>

#include <sstream>
#include <vector>

namespace pantocat
{
namespace
{
/// The entries of @p prm as "Subsection/.../Name" -> value.
std::map<std::string, std::string> entries_of(const dealii::ParameterHandler& prm)
{
  std::ostringstream text;
  prm.print_parameters(text, dealii::ParameterHandler::ShortPRM);
  std::istringstream lines(text.str());
  std::map<std::string, std::string> entries;
  std::vector<std::string> path;
  std::string line;
  while (std::getline(lines, line))
  {
    const std::size_t first = line.find_first_not_of(' ');
    if (first == std::string::npos)
      continue;
    line.erase(0, first);
    if (line.rfind("subsection ", 0) == 0)
      path.push_back(line.substr(11));
    else if (line == "end" && !path.empty())
      path.pop_back();
    else if (line.rfind("set ", 0) == 0 && line.find(" = ") != std::string::npos)
    {
      // print_parameters() pads the names so that the '=' line up.
      const std::size_t equals = line.find(" = ");
      const std::size_t name_end = line.find_last_not_of(' ', equals);
      std::string name;
      for (const std::string& s : path)
        name += s + "/";
      entries[name + line.substr(4, name_end - 3)] = line.substr(equals + 3);
    }
  }
  return entries;
}

void warn(std::ostream& err, const std::string& text)
{
  err << "pantocat-fem: warning: " << text << '\n';
}

/// "Pantograph/<model subsection>" of @p pantograph's models it does not use.
void warn_about_other_models(const std::map<std::string, std::string>& set,
                             const PantographCase& pantograph, std::ostream& err)
{
  const std::string prefix = pantograph.parameters.subsection + "/";
  const std::vector<std::pair<std::string, std::string>> models = {
      {"two-mass", "Two-mass model"},
      {"three-mass", "Three-mass model"},
      {"mass-chain", "Mass-chain model"}};
  for (const auto& [model, subsection] : models)
  {
    if (model == pantograph.model)
      continue;
    const std::string where = prefix + subsection + "/";
    for (const auto& [name, value] : set)
      if (name.rfind(where, 0) == 0)
      {
        warn(err, name + " = " + value + " is not used: " + pantograph.model_parameter() +
                      " = " + pantograph.model + " (the " + subsection +
                      " is used with " + pantograph.model_parameter() + " = " + model +
                      ")");
        break;
      }
  }
}
} // namespace

std::map<std::string, std::string> entries_set(const dealii::ParameterHandler& prm,
                                               const dealii::ParameterHandler& defaults)
{
  const std::map<std::string, std::string> declared = entries_of(defaults);
  std::map<std::string, std::string> set;
  for (const auto& [name, value] : entries_of(prm))
  {
    const auto d = declared.find(name);
    if (d == declared.end() || d->second != value)
      set[name] = value;
  }
  return set;
}

void warn_about_unused_entries(const std::map<std::string, std::string>& set,
                               const ProgramParameters& parameters, std::ostream& err)
{
  for (const PantographCase& pantograph : parameters.scene.pantographs)
  {
    if (!pantograph.has_body())
      continue;
    warn_about_other_models(set, pantograph, err);
    if (parameters.scene.start != Start::static_equilibrium ||
        parameters.mode != RunMode::dynamics)
      continue;
    for (const std::string entry : {"Initial contact force", "Initial offset",
                                    "Mass-chain model/Initial configuration"})
    {
      const auto it = set.find(pantograph.parameters.subsection + "/" + entry);
      if (it != set.end())
        warn(err, it->first + " = " + it->second +
                      " is not used: Run/Start = static equilibrium starts each contact "
                      "with the force its pantograph exerts at rest (Run/Start = paper "
                      "uses it)");
    }
  }
}
} // namespace pantocat
