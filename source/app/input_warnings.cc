#include <pantocat/app/input_warnings.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cctype>
#include <sstream>
#include <vector>

namespace pantocat
{
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

namespace
{
/// Edits (insert, delete, replace, swap two neighbours) from @p a to @p b, case ignored.
std::size_t edit_distance(const std::string& a, const std::string& b)
{
  const auto same = [](const char x, const char y)
  {
    return std::tolower(static_cast<unsigned char>(x)) ==
           std::tolower(static_cast<unsigned char>(y));
  };
  std::vector<std::vector<std::size_t>> d(a.size() + 1,
                                          std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i)
    d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j)
    d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
    for (std::size_t j = 1; j <= b.size(); ++j)
    {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1,
                          d[i - 1][j - 1] + (same(a[i - 1], b[j - 1]) ? 0 : 1)});
      if (i > 1 && j > 1 && same(a[i - 1], b[j - 2]) && same(a[i - 2], b[j - 1]))
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
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

std::string did_you_mean(const dealii::ParameterHandler& prm, const std::string& name,
                         const bool subsection)
{
  const std::size_t allowed = std::max<std::size_t>(2, name.size() / 4);
  std::map<std::size_t, std::vector<std::string>> candidates; // by distance
  for (const auto& entry : entries_of(prm))
  {
    // The path's components: subsections, then the entry's own name.
    const std::vector<std::string> parts =
        dealii::Utilities::split_string_list(entry.first, '/');
    for (std::size_t k = 0; k < parts.size(); ++k)
    {
      if ((k + 1 < parts.size()) != subsection)
        continue;
      const std::size_t d = edit_distance(name, parts[k]);
      std::string path;
      for (std::size_t i = 0; i <= k; ++i)
        path += (i ? "/" : "") + parts[i];
      auto& list = candidates[d];
      if (d <= allowed && std::find(list.begin(), list.end(), path) == list.end())
        list.push_back(path);
    }
  }
  if (candidates.empty() || candidates.begin()->first > allowed)
    return "";
  const std::vector<std::string>& best = candidates.begin()->second;
  std::string text = "did you mean ";
  for (std::size_t i = 0; i < std::min<std::size_t>(best.size(), 3); ++i)
    text += (i ? (i + 1 == std::min<std::size_t>(best.size(), 3) ? " or " : ", ") : "") +
            best[i];
  return text + "?";
}

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
