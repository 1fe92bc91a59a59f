// Property test of the unilateral forces (doc/impacts.md): random cases of
// the paper's span repeated into short sections, with random pantograph
// counts, speeds, speed ramps, contact and dropper laws, discretisations and
// integrators, each run by pantocat-fem (no shell, a time limit). Every
// output is scanned for two broken promises:
//  - a negative force of a unilateral constraint: the columns lambda_p* and
//    lambda_d* of time_series.csv, lambda_p* of contact_force.csv (not the
//    low-pass filtered column: a filtered signal may undershoot zero),
//    the raw minima of summary.json, the raw "min" column of a speed sweep
//    (every SWEEP_EVERY-th case). A unilateral force is never negative: the
//    text of a written one never starts with '-';
//  - a run that ends short: the leading pantograph (pantograph 1; the
//    others follow it at the spacing) ends at its Final position (to 1e-6 m,
//    round-off of x_p = x_0 + v t).
// Exit status 2 (a case refused before it starts, e.g. a half-explicit step
// above the stability limit) is counted, not checked; any other status but
// 0 is a failure. Each case has its own seed, printed with the command line
// that reproduces it; a failing case's directory is kept.
//
//   unilateral_forces EXE SOURCE_DIR WORKDIR CASES SEED [ramps|no-ramps]
//                     [SWEEP_EVERY] [TIME_LIMIT_SECONDS]
#include "child_process.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <random>
#include <sstream>

namespace fs = std::filesystem;

namespace
{
/// One generated case: its --set entries and what the checks need.
struct Case
{
  unsigned long seed = 0;
  std::vector<std::pair<std::string, std::string>> entries;
  double final_position = 0.; ///< of pantograph 1 [m]
  double speed = 0.;          ///< [m/s]
  std::string kind;           ///< integrator, discretisation, contact law

  std::string entry(const std::string& name) const
  {
    for (const auto& [n, v] : entries)
      if (n == name)
        return v;
    return "";
  }
};

std::string number(const double x)
{
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

/// @p x as the program reads it from number(x).
double rounded(const double x)
{
  return std::strtod(number(x).c_str(), nullptr);
}

/// The generator of one case from its seed.
class Generator
{
public:
  Generator(const unsigned long seed, const bool ramps) : random(seed), ramps(ramps) {}

  Case make(const unsigned long seed)
  {
    Case c;
    c.seed = seed;
    const auto set = [&](const std::string& name, const std::string& value)
    { c.entries.emplace_back(name, value); };
    const char* integrators[] = {"half-explicit", "bdf2", "generalized-alpha", "ida"};
    const std::string integrator = integrators[weighted({3, 3, 3, 1})];
    // IDA's variable steps are the slowest: one span for it.
    const unsigned int spans = integrator == "ida" ? 1 : pick(1, 3);
    const double length = 20. * spans;
    set("Catenary/Number of spans", std::to_string(spans));
    if (spans > 1 && chance(0.5))
      set("Catenary/Supports/Steady arm stiffness", number(uniform(1000., 5000.)));
    const bool elastic_droppers = chance(0.25);
    set("Scene/Droppers", elastic_droppers ? "elastic" : "unilateral");
    const bool penalty = chance(0.4);
    set("Scene/Contact", penalty ? "penalty" : "unilateral");
    if (penalty)
    {
      set("Scene/Contact stiffness", number(std::pow(10., uniform(4.3, 6.))));
      set("Scene/Contact damping", chance(0.5) ? "0" : number(uniform(0., 50.)));
    }
    // FEM with the implicit methods (the half-explicit one's FEM step is ten
    // times smaller, Sec. 6; IDA's variable steps on FEM take minutes).
    const bool fem =
        (integrator == "bdf2" || integrator == "generalized-alpha") && chance(0.5);
    set("Discretisation/Method", fem ? "fem" : "fdm");
    // h = 0.04 m (the paper's grid) or 0.08 m, both below the load's half-width 0.2 m.
    const unsigned int per_span = chance(0.5) ? 500 : 250;
    set("Discretisation/Number of intervals", std::to_string(per_span * spans));
    set("Time integration/Integrator", integrator);
    const double dt = integrator == "half-explicit" ? (per_span == 500 ? 2.5e-5 : 5e-5)
                      : chance(0.5)                 ? 5e-5
                                                    : 1e-4;
    set("Time integration/Time step", number(dt));
    // Pantographs: 1 to 3, the others (k - 1) s behind pantograph 1.
    const unsigned int pantographs = pick(1, 3);
    const double spacing = pantographs > 1 ? rounded(uniform(1.5, 4.)) : 0.;
    const double x0 = rounded(0.5 + (pantographs - 1) * spacing + uniform(0.2, 2.));
    const double travel = std::min(uniform(4., 16.), length - 1. - x0);
    c.speed = rounded(uniform(25., 70.));
    c.final_position = rounded(x0 + travel);
    set("Scene/Number of pantographs", std::to_string(pantographs));
    if (pantographs > 1)
      set("Scene/Pantograph spacing", number(spacing));
    set("Pantograph/Speed", number(c.speed));
    set("Pantograph/Initial position", number(x0));
    set("Pantograph/Final position", number(c.final_position));
    set("Pantograph/Initial offset", chance(0.5) ? "0" : "0.002");
    // A ramp that ends before the final position: v T_r / 2 < travel.
    if (ramps && chance(0.4))
      set("Pantograph/Speed ramp",
          number(std::min(uniform(0.01, 0.1), travel / c.speed)));
    if (chance(0.5))
      set("Statistics/Low-pass cut-off", "20");
    set("Output/Plots", "false");
    set("Output/Verbosity", "quiet");
    c.kind = integrator + ", " + (fem ? "fem" : "fdm") + ", " +
             (penalty ? "penalty" : "rigid") + " contact, " +
             (elastic_droppers ? "elastic" : "rigid") + " droppers, " +
             std::to_string(pantographs) + " pantograph(s)";
    return c;
  }

private:
  bool chance(const double p)
  {
    return std::uniform_real_distribution<>(0., 1.)(random) < p;
  }
  double uniform(const double a, const double b)
  {
    return std::uniform_real_distribution<>(a, b)(random);
  }
  unsigned int pick(const unsigned int a, const unsigned int b)
  {
    return std::uniform_int_distribution<unsigned int>(a, b)(random);
  }
  unsigned int weighted(const std::vector<double>& w)
  {
    return std::discrete_distribution<unsigned int>(w.begin(), w.end())(random);
  }

  std::mt19937_64 random;
  bool ramps;
};

std::vector<std::string> arguments(const Case& c, const fs::path& source,
                                   const fs::path& out,
                                   const std::vector<std::string>& extra = {})
{
  std::vector<std::string> a{(source / "prm/benchmark-48.prm").string()};
  for (const auto& [name, value] : c.entries)
    a.insert(a.end(), {"--set", name + "=" + value});
  for (const std::string& e : extra)
    a.insert(a.end(), {"--set", e});
  a.insert(a.end(), {"-o", out.string()});
  return a;
}

std::string command_line(const std::vector<std::string>& a)
{
  std::string line = "pantocat-fem";
  for (const std::string& s : a)
    line += s.find_first_of(" ,") == std::string::npos ? " " + s : " \"" + s + "\"";
  return line;
}

std::vector<std::string> fields(const std::string& line)
{
  std::vector<std::string> f;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ','))
    f.push_back(field);
  return f;
}

/**
 * The first negative entry of the columns of CSV @p file whose names
 * @p wanted accepts ("" if none): a '-' in front of a number is a negative
 * force, -0 included (a force never written as "-0").
 */
template <typename Wanted>
std::string first_negative(const fs::path& file, Wanted wanted)
{
  const std::vector<std::string> lines = fuzz::lines_of(fuzz::read_file(file.string()));
  if (lines.empty())
    return file.filename().string() + " is missing or empty";
  const std::vector<std::string> names = fields(lines[0]);
  std::vector<std::size_t> columns;
  for (std::size_t i = 0; i < names.size(); ++i)
    if (wanted(names[i]))
      columns.push_back(i);
  for (std::size_t r = 1; r < lines.size(); ++r)
  {
    const std::vector<std::string> row = fields(lines[r]);
    for (const std::size_t i : columns)
      if (i >= row.size() || row[i].empty() || row[i][0] == '-' ||
          !std::isfinite(std::strtod(row[i].c_str(), nullptr)))
        return file.filename().string() + ": " + names[i] + " = " +
               (i < row.size() ? row[i] : "(missing)") + " in row " + std::to_string(r) +
               " (" + names[0] + " = " + row[0] + ")";
  }
  return "";
}

bool starts_with(const std::string& s, const std::string& prefix)
{
  return s.rfind(prefix, 0) == 0;
}

/// x_p of pantograph 1 in the last row of time_series.csv, or NaN.
double final_position_written(const fs::path& file)
{
  const std::vector<std::string> lines = fuzz::lines_of(fuzz::read_file(file.string()));
  if (lines.size() < 2)
    return NAN;
  const std::vector<std::string> names = fields(lines[0]), last = fields(lines.back());
  for (std::size_t i = 0; i < names.size() && i < last.size(); ++i)
    if (names[i] == "x_p" || names[i] == "x_p[1]")
      return std::strtod(last[i].c_str(), nullptr);
  return NAN;
}

/// The raw minima of summary.json ("" if all >= 0).
std::string negative_summary_minimum(const fs::path& file)
{
  nlohmann::json j;
  try
  {
    j = nlohmann::json::parse(fuzz::read_file(file.string()));
  }
  catch (const std::exception& e)
  {
    return "summary.json does not parse: " + std::string(e.what());
  }
  if (j.value("status", "") != "completed")
    return "summary.json says " + j.value("status", std::string("nothing"));
  std::vector<std::pair<std::string, const nlohmann::json*>> minima;
  if (j.contains("contact_force"))
    minima.emplace_back("contact_force.min", &j["contact_force"]["min"]);
  if (j.contains("statistics"))
    minima.emplace_back("statistics.raw.min", &j["statistics"]["raw"]["min"]);
  for (std::size_t k = 0; k < j["pantographs"].size(); ++k)
  {
    const nlohmann::json& p = j["pantographs"][k];
    const std::string where = "pantographs[" + std::to_string(k) + "].";
    if (p.contains("contact_force"))
      minima.emplace_back(where + "contact_force.min", &p["contact_force"]["min"]);
    if (p.contains("statistics"))
      minima.emplace_back(where + "statistics.raw.min", &p["statistics"]["raw"]["min"]);
  }
  for (const auto& [name, value] : minima)
    if (!value->is_number() || value->get<double>() < 0. ||
        std::signbit(value->get<double>()))
      return "summary.json: " + name + " = " + value->dump();
  return "";
}

/// What a completed run @p out broke ("" if nothing).
std::string broken_promise(const Case& c, const fs::path& out)
{
  const auto force = [](const std::string& n)
  { return starts_with(n, "lambda_p") || starts_with(n, "lambda_d"); };
  if (std::string why = first_negative(out / "time_series.csv", force); !why.empty())
    return why;
  const auto raw_contact = [](const std::string& n)
  { return starts_with(n, "lambda_p") && n.find("filtered") == std::string::npos; };
  if (std::string why = first_negative(out / "contact_force.csv", raw_contact);
      !why.empty())
    return why;
  if (std::string why = negative_summary_minimum(out / "summary.json"); !why.empty())
    return why;
  const double x = final_position_written(out / "time_series.csv");
  if (!(std::abs(x - c.final_position) <= 1e-6))
    return "the run ends short: pantograph 1 at x_p = " + number(x) +
           " m, its Final position is " + number(c.final_position) + " m";
  return "";
}

/// The speed sweep of case @p c over its speed and 1.2 times it: every row
/// completed, its raw "min" >= 0 ("" if so).
std::string broken_sweep(const Case& c, const std::string& exe, const fs::path& source,
                         const fs::path& dir, const double limit)
{
  const double kmh = c.speed * 3.6;
  const auto a = arguments(
      c, source, dir / "sweep",
      {"Run/Mode=speed sweep", "Sweep/Speeds=" + number(kmh) + ", " + number(1.2 * kmh)});
  const fuzz::Outcome o =
      fuzz::run(exe, a, dir.string(), (dir / "sweep-run").string(), limit);
  if (o.exit_status == 2)
    return "";
  if (o.exit_status != 0)
    return "the sweep ended with " +
           (o.timed_out ? std::string("the time limit")
                        : "exit " + std::to_string(o.exit_status)) +
           ": " + o.err + "\n  reproduce: " + command_line(a);
  const fs::path table = dir / "sweep" / "speed_sweep.csv";
  std::string why =
      first_negative(table, [](const std::string& n) { return n == "min"; });
  const std::vector<std::string> lines = fuzz::lines_of(fuzz::read_file(table.string()));
  for (std::size_t r = 1; why.empty() && r < lines.size(); ++r)
    if (lines[r].find(",completed,") == std::string::npos)
      why = "speed_sweep.csv row " + std::to_string(r) + " is not completed: " + lines[r];
  return why.empty() ? "" : why + "\n  reproduce: " + command_line(a);
}
} // namespace

int main(int argc, char** argv)
{
  if (argc < 6)
  {
    std::cerr << "usage: unilateral_forces EXE SOURCE_DIR WORKDIR CASES SEED "
                 "[ramps|no-ramps] [SWEEP_EVERY] [TIME_LIMIT]\n";
    return 2;
  }
  const std::string exe = fs::absolute(argv[1]).string();
  const fs::path source = fs::absolute(argv[2]), work = fs::absolute(argv[3]);
  const unsigned long n_cases = std::strtoul(argv[4], nullptr, 10);
  const unsigned long seed = std::strtoul(argv[5], nullptr, 10);
  const bool ramps = argc > 6 ? std::string(argv[6]) == "ramps" : true;
  const unsigned long sweep_every = argc > 7 ? std::strtoul(argv[7], nullptr, 10) : 0;
  const double limit = argc > 8 ? std::strtod(argv[8], nullptr) : 300.;
  fs::remove_all(work);
  fs::create_directories(work);

  std::map<std::string, unsigned int> outcomes;
  unsigned long failed = 0, checked = 0, sweeps = 0;
  double total = 0., slowest = 0.;
  for (unsigned long k = 0; k < n_cases; ++k)
  {
    // Each case from its own seed: one case is reproduced without the others.
    const unsigned long case_seed = seed * 1000003ul + k;
    Generator generate(case_seed, ramps);
    const Case c = generate.make(case_seed);
    const fs::path dir = work / ("case-" + std::to_string(k));
    fs::create_directories(dir);
    const auto a = arguments(c, source, dir / "out");
    const fuzz::Outcome o =
        fuzz::run(exe, a, dir.string(), (dir / "run").string(), limit);
    total += o.seconds;
    slowest = std::max(slowest, o.seconds);
    std::string why;
    if (o.timed_out)
      why = "the time limit of " + number(limit) + " s";
    else if (o.exit_status == 2)
      ++outcomes["refused before the start (exit 2)"];
    else if (o.exit_status != 0)
      why = "exit " + std::to_string(o.exit_status) + ": " + o.err;
    else
    {
      ++checked;
      ++outcomes["completed and checked"];
      why = broken_promise(c, dir / "out");
      if (why.empty() && sweep_every > 0 && k % sweep_every == 0 &&
          c.entry("Time integration/Integrator") != "ida")
      {
        ++sweeps;
        why = broken_sweep(c, exe, source, dir, limit);
      }
    }
    std::cout << "case " << k << " (seed " << case_seed << "; " << c.kind
              << "): " << (why.empty() ? "passed" : "FAILED") << " in "
              << number(o.seconds) << " s\n";
    if (why.empty())
    {
      fs::remove_all(dir);
      continue;
    }
    ++failed;
    std::cout << "  " << why << "\n  reproduce: " << command_line(a) << "\n  kept in "
              << dir.string() << "\n";
  }
  std::cout << n_cases << " cases from seed " << seed << (ramps ? ", with" : ", without")
            << " speed ramps; " << sweeps << " speed sweeps; " << total
            << " s of runs, slowest " << slowest << " s\n";
  for (const auto& [outcome, count] : outcomes)
    std::cout << "  " << outcome << ": " << count << "\n";
  std::cout << n_cases - failed << " passed, " << failed << " failed\n";
  // A property checked on no case is no check: at least half must run.
  if (2 * checked < n_cases)
  {
    std::cout << "only " << checked << " of " << n_cases << " cases ran to completion\n";
    return 1;
  }
  return failed == 0 ? 0 : 1;
}
