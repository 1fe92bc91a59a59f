// Fuzz test of pantocat-fem's input (doc/input-errors.md): prm files and
// --set values generated from the declared parameters (`pantocat-fem
// --print-parameters json` gives every entry with its pattern), with a fixed
// seed. Each case runs the program (no shell, a time limit, killed after it)
// on a very short run of a shipped prm file and checks the promises:
//  - the exit status is 0, 1 or 2; never a signal, never the time limit;
//  - exit 2: exactly one line on stderr, and no output directory left;
//  - exit 1: summary.json says "failed", with a reason;
//  - exit 0: summary.json (if the mode writes one) is valid JSON, says
//    "completed", and all its numbers are finite; the CSV files hold no
//    non-finite number.
// It prints each failing case (its prm file and command line are kept in
// WORKDIR/failed-NNNN), the counts per outcome and per kind of mutation, and
// a closing line "N passed, N failed".
//
//   prm_fuzz EXE SOURCE_DIR WORKDIR CASES [SEED] [TIME_LIMIT_SECONDS]
#include "child_process.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iostream>
#include <map>
#include <random>
#include <regex>

namespace fs = std::filesystem;

namespace
{
/// A declared pattern of deal.II (its description, as --print-parameters prints it).
struct Pattern
{
  enum class Kind
  {
    integer,
    real,
    boolean,
    selection,
    list,
    text
  } kind = Kind::text;
  double lower = -HUGE_VAL, upper = HUGE_VAL;
  std::vector<std::string> choices;             ///< of a selection
  std::shared_ptr<Pattern> element;             ///< of a list
  unsigned long min_length = 0, max_length = 0; ///< of a list
};

/// One declared entry: "Subsection/.../Name", its default and pattern.
struct Entry
{
  std::vector<std::string> path; ///< subsections, then the name
  std::string default_value;
  Pattern pattern;
  std::string name() const
  {
    std::string joined;
    for (const auto& p : path)
      joined += (joined.empty() ? "" : "/") + p;
    return joined;
  }
};

double bound(const std::string& text)
{
  if (text == "MAX_DOUBLE")
    return HUGE_VAL;
  if (text == "-MAX_DOUBLE")
    return -HUGE_VAL;
  return std::strtod(text.c_str(), nullptr);
}

Pattern parse_pattern(const std::string& d)
{
  Pattern p;
  std::smatch m;
  if (std::regex_match(d, m, std::regex(R"(\[Integer range (\S+)\.\.\.(\S+) .*\])")))
    p.kind = Pattern::Kind::integer, p.lower = bound(m[1]), p.upper = bound(m[2]);
  else if (std::regex_match(d, m, std::regex(R"(\[Double (\S+)\.\.\.(\S+) .*\])")))
    p.kind = Pattern::Kind::real, p.lower = bound(m[1]), p.upper = bound(m[2]);
  else if (d == "[Bool]")
    p.kind = Pattern::Kind::boolean;
  else if (std::regex_match(d, m, std::regex(R"(\[Selection (.*) \])")))
  {
    p.kind = Pattern::Kind::selection;
    std::stringstream choices(m[1].str());
    for (std::string c; std::getline(choices, c, '|');)
      p.choices.push_back(c);
  }
  else if (std::regex_match(
               d, m, std::regex(R"(\[List of <(.*)> of length (\d+)\.\.\.(\d+) .*\])")))
  {
    p.kind = Pattern::Kind::list;
    p.element = std::make_shared<Pattern>(parse_pattern(m[1]));
    p.min_length = std::stoul(m[2]);
    p.max_length = std::stoul(m[3]);
  }
  return p;
}

void collect_entries(const nlohmann::ordered_json& node, std::vector<std::string> path,
                     std::vector<Entry>& entries)
{
  for (const auto& [key, value] : node.items())
  {
    if (!value.is_object())
      continue;
    auto here = path;
    here.push_back(key);
    if (value.contains("pattern_description"))
      entries.push_back({here, value["default_value"].get<std::string>(),
                         parse_pattern(value["pattern_description"].get<std::string>())});
    else
      collect_entries(value, here, entries);
  }
}

/// A generated case: a prm file, its --set settings, the files it includes.
struct Case
{
  std::string kind; ///< of its (last) mutation
  std::string prm;
  std::vector<std::string> sets;
  std::vector<std::pair<std::string, std::string>> files; ///< name, content
  std::vector<std::string> options;                       ///< further arguments
};

std::string format(const double x)
{
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

/// The generator of cases, with its random source.
class Generator
{
public:
  Generator(std::vector<Entry> entries, std::vector<std::string> bases,
            const unsigned int seed)
      : entries(std::move(entries)), bases(std::move(bases)), random(seed)
  {
  }

  Case next()
  {
    Case c;
    c.prm = "include " + pick(bases) +
            "\n# very short runs: x_p from 2 to 2.2 m, no gnuplot\n"
            "subsection Pantograph\n  set Final position = 2.2\nend\n"
            "subsection Output\n  set Plots = false\nend\n";
    // Mostly one mutation, so that a valid one is not hidden behind a refusal.
    const int n = pick(std::vector<int>{1, 1, 1, 1, 2, 2, 3});
    for (int k = 0; k < n; ++k)
      mutate(c);
    return c;
  }

private:
  using Mutation = std::function<void(Case&)>;

  int uniform(const int a, const int b)
  {
    return std::uniform_int_distribution<int>(a, b)(random);
  }
  double real(const double a, const double b)
  {
    return std::uniform_real_distribution<double>(a, b)(random);
  }
  template <typename T>
  const T& pick(const std::vector<T>& list)
  {
    return list[uniform(0, static_cast<int>(list.size()) - 1)];
  }

  /// A value the pattern accepts, near the default (so that runs stay short).
  std::string valid_value(const Pattern& p, const std::string& default_value)
  {
    switch (p.kind)
    {
    case Pattern::Kind::integer:
    {
      const double d = std::strtod(default_value.c_str(), nullptr);
      double x = d == 0. ? pick(std::vector<double>{0., 1., 2., 10.})
                         : std::round(d * std::pow(2., real(-1., 1.)));
      return format(std::clamp(x, p.lower, p.upper));
    }
    case Pattern::Kind::real:
    {
      const double d = std::strtod(default_value.c_str(), nullptr);
      const double x = d == 0. ? pick(std::vector<double>{0., 1e-3, 0.1, 1.})
                               : d * std::pow(2., real(-1., 1.));
      return format(std::clamp(x, p.lower, p.upper));
    }
    case Pattern::Kind::boolean:
      return uniform(0, 1) ? "true" : "false";
    case Pattern::Kind::selection:
    {
      // Not the study and sweep modes: each runs many dynamic runs on grids
      // up to N+1 = 8000 (minutes); their input checks have their own tests.
      std::vector<std::string> choices;
      for (const auto& c : p.choices)
        if (c != "convergence study" && c != "work precision" && c != "speed sweep" &&
            c != "parameter sweep" && c != "monte carlo")
          choices.push_back(c);
      return pick(choices);
    }
    case Pattern::Kind::list:
    {
      if (uniform(0, 1) == 0 || !p.element)
        return default_value;
      const unsigned long n =
          std::min<unsigned long>(p.min_length + uniform(0, 3), p.max_length);
      std::string list;
      for (unsigned long k = 0; k < n; ++k)
        list += (k ? ", " : "") + valid_value(*p.element, "1");
      return list;
    }
    default:
      return default_value;
    }
  }

  /// A value on the edge of the pattern's range: its bound, or 0 if unbounded.
  std::string boundary(const Pattern& p)
  {
    if (p.kind == Pattern::Kind::list)
      return p.min_length == 0 ? "" : "0, 0, 0";
    if (p.kind != Pattern::Kind::integer && p.kind != Pattern::Kind::real)
      return "";
    if (p.upper < HUGE_VAL && uniform(0, 2) == 0)
      return format(p.upper);
    return format(p.lower > -HUGE_VAL ? p.lower : 0.);
  }

  /// A value outside the pattern's range (or not one of its words).
  std::string out_of_range(const Pattern& p)
  {
    if (p.kind == Pattern::Kind::selection)
      return p.choices.front() + "x";
    if (p.kind == Pattern::Kind::list)
      return "1, 2, 3, 4, 5, 6, 7, 8, 9, 10, -1e300";
    if (p.lower > -HUGE_VAL && uniform(0, 1) == 0)
      return format(p.lower - 1.);
    if (p.upper < HUGE_VAL)
      return format(p.upper + 1.);
    return "-1";
  }

  /// Sets @p entry to @p value, in the prm file or by --set.
  void set(Case& c, const Entry& entry, const std::string& value, const bool by_set)
  {
    if (by_set)
    {
      c.sets.push_back(entry.name() + "=" + value);
      return;
    }
    for (std::size_t k = 0; k + 1 < entry.path.size(); ++k)
      c.prm += "subsection " + entry.path[k] + "\n";
    c.prm += "  set " + entry.path.back() + " = " + value + "\n";
    for (std::size_t k = 0; k + 1 < entry.path.size(); ++k)
      c.prm += "end\n";
  }

  void mutate(Case& c)
  {
    const std::vector<std::pair<std::string, Mutation>> mutations = {
        {"valid",
         [&](Case& c)
         {
           set_value(c, [&](const Entry& e)
                     { return valid_value(e.pattern, e.default_value); });
         }},
        {"boundary", [&](Case& c)
         { set_value(c, [&](const Entry& e) { return boundary(e.pattern); }); }},
        {"out_of_range", [&](Case& c)
         { set_value(c, [&](const Entry& e) { return out_of_range(e.pattern); }); }},
        {"wrong_type",
         [&](Case& c)
         {
           set_value(c,
                     [&](const Entry&)
                     {
                       return pick(std::vector<std::string>{
                           "abc", "1.5.3", "true", "1e", "--", "3.5", "fem fdm", "0x10",
                           "= 2", "\\", "{abc}", "{1|2}"});
                     });
         }},
        {"list",
         [&](Case& c)
         {
           set_value(c,
                     [&](const Entry&)
                     {
                       return pick(std::vector<std::string>{"1, 2", "1,,2", ",", "1, abc",
                                                            "5.5, 25, 30",
                                                            "fem, fdm, fem", "1 2 3"});
                     });
         }},
        {"huge",
         [&](Case& c)
         {
           set_value(c,
                     [&](const Entry&)
                     {
                       return pick(std::vector<std::string>{
                           "1e300", "-1e300", "1e-300", "2147483647", "-2147483648",
                           "99999999999999999999", "1e309", "4294967296"});
                     });
         }},
        {"nan",
         [&](Case& c)
         {
           set_value(c,
                     [&](const Entry&)
                     {
                       return pick(std::vector<std::string>{"nan", "NaN", "inf", "-inf",
                                                            "infinity", "-nan"});
                     });
         }},
        {"non_utf8",
         [&](Case& c)
         {
           set_value(c, [&](const Entry&)
                     { return std::string("\xff\xfe\x80 caf\xe9 \xc3"); });
         }},
        {"control", [&](Case& c) { control_character(c); }},
        {"include", [&](Case& c) { include(c); }},
        {"structure", [&](Case& c) { structure(c); }},
        {"command_line", [&](Case& c) { command_line(c); }}};
    // Valid values are drawn as often as all kinds of bad input together: the
    // runs they start are where crashes and hangs hide.
    const auto& [kind, mutation] =
        uniform(0, 1) == 0 ? mutations.front() : pick(mutations);
    c.kind = kind;
    mutation(c);
  }

  void set_value(Case& c, const std::function<std::string(const Entry&)>& value)
  {
    const Entry& e = pick(entries);
    set(c, e, value(e), uniform(0, 1) == 0);
  }

  void control_character(Case& c)
  {
    const Entry& e = pick(entries);
    std::string value = valid_value(e.pattern, e.default_value);
    const char control = static_cast<char>(uniform(1, 31));
    value.insert(uniform(0, static_cast<int>(value.size())), 1, control);
    // A newline in a prm line only ends it; in --set it must be refused.
    set(c, e, value, control == '\n' || uniform(0, 1) == 0);
  }

  void include(Case& c)
  {
    switch (uniform(0, 5))
    {
    case 0: // a file with a valid setting
    {
      const Entry& e = pick(entries);
      Case inner;
      set(inner, e, valid_value(e.pattern, e.default_value), false);
      c.files.emplace_back("inner.prm", inner.prm);
      c.prm += "include inner.prm\n";
      break;
    }
    case 1:
      c.prm += "include case.prm\n";
      break;
    case 2:
      c.files.emplace_back("a.prm", "include b.prm\n");
      c.files.emplace_back("b.prm", "subsection Catenary\n  include a.prm\nend\n");
      c.prm += "include a.prm\n";
      break;
    case 3:
      c.prm += "include .\n";
      break;
    case 4:
      c.prm += "include no-such-file.prm\n";
      break;
    default:
      c.prm += pick(std::vector<std::string>{"include /dev/null\n", "include\n",
                                             "include /dev/zero\n"});
    }
  }

  void structure(Case& c)
  {
    c.prm += pick(std::vector<std::string>{
        "subsection Foo\nend\n", "end\n", "subsection Catenary\n", "set = 5\n", "xyz\n",
        "subsection Catenary\n  set Lenght = 20\nend\n", "set Span = 20\n",
        "subsection Catenary\n  set Span = 20 \\\nend\n", std::string(1, '\0') + "\n",
        "subsection Catenary\n  set Span\nend\n", std::string(70000, 'x') + "\n"});
  }

  void command_line(Case& c)
  {
    switch (uniform(0, 4))
    {
    case 0:
      c.options.push_back("--bogus");
      break;
    case 1:
      c.options = {"--print-parameters",
                   pick(std::vector<std::string>{"xml", "", "prm "})};
      break;
    case 2:
      c.sets.push_back(pick(std::vector<std::string>{
          "Catenary/Span", "=5", "/Span=5", "Catenary//Span=5", "Catenary/Span==5",
          "Catenary/Span=5\nend\nsubsection Output\nset Plots = false",
          "Output/Output directory=", "Catenary/Span=20 # comment"}));
      break;
    case 3:
      c.options.push_back("second.prm");
      break;
    default:
      c.options.push_back("--set");
    }
  }

  std::vector<Entry> entries;
  std::vector<std::string> bases;
  std::mt19937 random;
};

/// The result files of any mode (README); none may stay after bad input.
bool non_finite_in_csv(const fs::path& dir)
{
  if (!fs::is_directory(dir))
    return false;
  const std::regex non_finite(R"((^|,)[-+]?(nan|inf)(,|$))", std::regex::icase);
  for (const auto& f : fs::directory_iterator(dir))
    if (f.path().extension() == ".csv")
      for (const auto& line : fuzz::lines_of(fuzz::read_file(f.path().string())))
        if (std::regex_search(line, non_finite))
          return true;
  return false;
}

bool all_numbers_finite(const nlohmann::json& j)
{
  if (j.is_number_float())
    return std::isfinite(j.get<double>());
  if (j.is_structured())
    for (const auto& e : j)
      if (!all_numbers_finite(e))
        return false;
  return true;
}

/// The run mode written into out/parameters.prm ("" if there is none).
std::string mode_of(const fs::path& out)
{
  std::smatch m;
  const std::string prm = fuzz::read_file((out / "parameters.prm").string());
  const std::regex mode(R"(set Mode\s*=\s*([a-z ]*[a-z]))");
  return std::regex_search(prm, m, mode) ? m[1].str() : "";
}

std::string broken_exit_0(const fs::path& out, const std::string& mode)
{
  const fs::path summary = out / "summary.json";
  if (!fs::exists(summary))
    return mode == "dynamics" || mode == "static" || mode == "eigenfrequencies"
               ? "exit 0 without summary.json"
               : "";
  const auto j = nlohmann::json::parse(fuzz::read_file(summary.string()), nullptr, false);
  if (j.is_discarded())
    return "summary.json is not valid JSON";
  if (j.value("status", "") != "completed" || !all_numbers_finite(j))
    return "summary.json not completed or with a non-finite number";
  if (non_finite_in_csv(out))
    return "a CSV file holds a non-finite number";
  return "";
}

std::string broken_exit_1(const fs::path& out, const std::vector<std::string>& lines)
{
  // Every mode (the studies too) says a failure in summary.json, with the
  // phase it happened in, and on stderr.
  if (lines.empty() || lines.back().rfind("pantocat-fem: ", 0) != 0)
    return "exit 1 without a message";
  const fs::path summary = out / "summary.json";
  if (!fs::exists(summary))
    return "exit 1 without summary.json";
  const auto j = nlohmann::json::parse(fuzz::read_file(summary.string()), nullptr, false);
  if (j.is_discarded() || j.value("status", "") != "failed" ||
      j.value("reason", "").empty() || j.value("phase", "").empty())
    return "exit 1, but summary.json does not say failed with a phase and a reason";
  return "";
}

/// The broken promise of a case's outcome, or "" if it kept them all.
std::string broken_promise(const fuzz::Outcome& o, const fs::path& out)
{
  if (!o.started)
    return "the program did not start";
  if (o.timed_out)
    return "still running at the time limit (killed)";
  if (o.signal != 0)
    return "ended by signal " + std::to_string(o.signal);
  const auto lines = fuzz::lines_of(o.err);
  switch (o.exit_status)
  {
  case 2:
    if (lines.size() != 1)
      return "exit 2 with " + std::to_string(lines.size()) + " lines on stderr";
    if (fs::exists(out))
      return "exit 2 left the output directory behind";
    return "";
  case 1:
    return broken_exit_1(out, lines);
  case 0:
    return broken_exit_0(out, mode_of(out));
  default:
    return "exit status " + std::to_string(o.exit_status);
  }
}

/// The kind of a failure (exit 1): its last stderr line up to the first digit.
std::string failure_kind(const std::string& err)
{
  const auto lines = fuzz::lines_of(err);
  std::string line = lines.empty() ? "" : lines.back();
  if (line.rfind("pantocat-fem: ", 0) == 0)
    line = line.substr(14);
  line = line.substr(0, std::min(line.find_first_of("0123456789"), std::size_t(70)));
  return line;
}

std::vector<std::string> arguments_of(const Case& c)
{
  std::vector<std::string> arguments{"case.prm"};
  for (const auto& s : c.sets)
    arguments.insert(arguments.end(), {"--set", s});
  arguments.insert(arguments.end(), c.options.begin(), c.options.end());
  arguments.insert(arguments.end(), {"-o", "out"});
  return arguments;
}

void write_case(const fs::path& dir, const Case& c)
{
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "case.prm", std::ios::binary) << c.prm;
  for (const auto& [name, text] : c.files)
    std::ofstream(dir / name, std::ios::binary) << text;
}

/// Keeps a failing case with its command line in @p dir.
void keep_failure(const fs::path& dir, const Case& c, const fuzz::Outcome& o,
                  const std::string& why)
{
  std::ofstream note(dir / "FAILED.txt");
  note << why << "\narguments:";
  for (const auto& a : arguments_of(c))
    note << " [" << a << "]";
  note << "\nstderr:\n" << o.err;
}

std::vector<Entry> declared_entries(const std::string& exe, const fs::path& work)
{
  const auto o = fuzz::run(exe, {"--print-parameters", "json"}, work.string(),
                           (work / "parameters").string(), 60.);
  std::vector<Entry> entries;
  collect_entries(nlohmann::ordered_json::parse(o.out), {}, entries);
  return entries;
}

/// The shipped prm files but the studies (minutes per run; see valid_value()).
std::vector<std::string> base_files(const fs::path& source)
{
  std::vector<std::string> bases;
  for (const auto& dir : {source / "prm", source / "prm/scenes"})
    for (const auto& f : fs::directory_iterator(dir))
      if (f.path().extension() == ".prm" &&
          f.path().filename().string().find("convergence") == std::string::npos &&
          f.path().filename().string().find("work-precision") == std::string::npos)
        bases.push_back(f.path().string());
  std::sort(bases.begin(), bases.end());
  return bases;
}

} // namespace

int main(int argc, char** argv)
{
  if (argc < 5)
  {
    std::cerr << "usage: prm_fuzz EXE SOURCE_DIR WORKDIR CASES [SEED] [TIME_LIMIT]\n";
    return 2;
  }
  const std::string exe = fs::absolute(argv[1]).string();
  const fs::path source = fs::absolute(argv[2]), work = fs::absolute(argv[3]);
  const unsigned long n_cases = std::strtoul(argv[4], nullptr, 10);
  const unsigned int seed = argc > 5 ? std::strtoul(argv[5], nullptr, 10) : 4242;
  const double limit = argc > 6 ? std::strtod(argv[6], nullptr) : 30.;
  fs::remove_all(work);
  fs::create_directories(work);

  const auto entries = declared_entries(exe, work);
  Generator generate(entries, base_files(source), seed);
  std::map<std::string, unsigned int> outcomes;
  std::map<std::string, std::map<std::string, unsigned int>> by_kind;
  std::map<std::string, unsigned int> failures; ///< of the runs that exit 1
  unsigned long passed = 0, failed = 0;
  double slowest = 0., total = 0.;
  for (unsigned long k = 0; k < n_cases; ++k)
  {
    const Case c = generate.next();
    const fs::path dir = work / ("case-" + std::to_string(k));
    write_case(dir, c);
    const auto o =
        fuzz::run(exe, arguments_of(c), dir.string(), (dir / "run").string(), limit);
    slowest = std::max(slowest, o.seconds);
    total += o.seconds;
    const std::string outcome = o.timed_out ? "time limit"
                                : o.signal  ? "signal"
                                            : "exit " + std::to_string(o.exit_status);
    ++outcomes[outcome];
    ++by_kind[c.kind][outcome];
    if (o.exit_status == 1)
      ++failures[failure_kind(o.err)];
    const std::string why = broken_promise(o, dir / "out");
    if (why.empty())
    {
      ++passed;
      fs::remove_all(dir);
      continue;
    }
    ++failed;
    keep_failure(dir, c, o, why);
    std::cout << "FAILED case " << k << " (" << c.kind << "): " << why << "; kept in "
              << dir.string() << "\n";
  }
  std::cout << entries.size() << " declared entries; " << n_cases << " cases, seed "
            << seed << ", time limit " << limit << " s; " << total
            << " s in all, slowest " << slowest << " s\n";
  for (const auto& [outcome, count] : outcomes)
    std::cout << "  " << outcome << ": " << count << "\n";
  for (const auto& [kind, counts] : by_kind)
  {
    std::cout << "  " << kind << ":";
    for (const auto& [outcome, count] : counts)
      std::cout << " " << outcome << " " << count << ";";
    std::cout << "\n";
  }
  std::cout << "  exit 1, by message:\n";
  for (const auto& [kind, count] : failures)
    std::cout << "    " << count << " x " << kind << "...\n";
  std::cout << passed << " passed, " << failed << " failed\n";
  return failed == 0 ? 0 : 1;
}
