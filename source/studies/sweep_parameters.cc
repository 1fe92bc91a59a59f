#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>
#include <pantocat/base/safe_files.h>
#include <pantocat/studies/sweep_parameters.h>

#include <deal.II/base/utilities.h>

#include <cmath>
#include <map>
#include <sstream>

namespace pantocat
{
namespace
{
/// @p text as a finite double, or false.
bool to_number(const std::string& text, double& value)
{
  const std::string t = dealii::Utilities::trim(text);
  if (t.empty())
    return false;
  std::istringstream in(t);
  in >> value;
  return !in.fail() && in.eof() && std::isfinite(value);
}

/// "a to b step s" split into its three numbers; false if @p text is no range.
bool parse_range(const std::string& text, double& first, double& last, double& step)
{
  const auto to = text.find(" to ");
  const auto by = text.find(" step ");
  if (to == std::string::npos || by == std::string::npos || by < to)
    return false;
  return to_number(text.substr(0, to), first) &&
         to_number(text.substr(to + 4, by - to - 4), last) &&
         to_number(text.substr(by + 6), step);
}

/// The text of the values of a range, printed with up to 12 digits.
std::vector<std::string> as_text(const std::vector<double>& values)
{
  std::vector<std::string> text;
  for (const double v : values)
    text.push_back(number_to_string(v, 12));
  return text;
}

/**
 * Refuses two values of a sweep that are the same run: @p same[i] is value
 * i as the run sees it (its number, or its text in the CSV), @p written[i]
 * as written. Names the first value given more than once.
 */
void require_distinct(const std::vector<std::string>& same,
                      const std::vector<std::string>& written,
                      const std::string& parameter, const std::string& text)
{
  std::map<std::string, std::vector<std::size_t>> where;
  for (std::size_t i = 0; i < same.size(); ++i)
    where[same[i]].push_back(i);
  for (std::size_t i = 0; i < same.size(); ++i)
  {
    const std::vector<std::size_t>& at = where[same[i]];
    if (at.size() == 1)
      continue;
    std::string as;
    for (const std::size_t j : at)
      as += (as.empty() ? "" : ", ") + written[j];
    require(false, parameter, text,
            "the value " + written[i] + " is given " + std::to_string(at.size()) +
                " times (as " + as +
                "), which would run the same case again; allowed: each value once");
  }
}

/// The values of an entry as written: a list of words, or a range expanded.
std::vector<std::string> value_words(const std::string& text,
                                     const std::string& parameter)
{
  if (text.find(" to ") != std::string::npos)
    return as_text(parse_sweep_values(text, parameter));
  std::vector<std::string> words;
  for (const std::string& w : dealii::Utilities::split_string_list(text))
    words.push_back(dealii::Utilities::trim(w));
  require(!words.empty(), parameter, text,
          "give at least one value: a list \"a, b, c\" or a range \"first to last "
          "step s\"");
  return words;
}

/// Refuses a list of @p words in which two are the same number (or the same text).
void require_distinct_values(const std::vector<std::string>& words,
                             const std::string& parameter, const std::string& text)
{
  std::vector<std::string> same;
  for (const std::string& w : words)
  {
    double v = 0.;
    same.push_back(to_number(w, v) ? number_to_string(v, 17) : w);
  }
  require_distinct(same, words, parameter, text);
}

/**
 * Refuses two speeds that are the same run or the same key in the CSV (the
 * speeds printed with 12 digits, speed_kmh).
 */
void require_distinct_speeds(const std::vector<double>& speeds, const std::string& text)
{
  std::vector<std::string> keys, written;
  for (const double v : speeds)
    keys.push_back(number_to_string(v, 12));
  if (text.find(" to ") != std::string::npos)
    written = keys;
  else
    for (const std::string& w : dealii::Utilities::split_string_list(text))
      written.push_back(dealii::Utilities::trim(w));
  require_distinct(keys, written.size() == keys.size() ? written : keys, "Sweep/Speeds",
                   text);
}
} // namespace

std::vector<double> parse_sweep_values(const std::string& text,
                                       const std::string& parameter)
{
  const std::string allowed =
      "a list \"a, b, c\" or a range \"first to last step s\" with first <= last "
      "and s > 0";
  std::vector<double> values;
  double first = 0., last = 0., step = 0.;
  if (text.find(" to ") != std::string::npos)
  {
    require(parse_range(text, first, last, step), parameter, text, allowed);
    require(step > 0. && first <= last, parameter, text,
            "an empty range; allowed: " + allowed);
    const double n = std::floor((last - first) / step + 1e-9);
    require(n < 1e5, parameter, text, "more than 100000 values; allowed: " + allowed);
    for (long i = 0; i <= static_cast<long>(n); ++i)
      values.push_back(first + i * step);
    return values;
  }
  for (const std::string& word : dealii::Utilities::split_string_list(text))
  {
    double v = 0.;
    require(to_number(word, v), parameter, text,
            "\"" + word + "\" is not a number; allowed: " + allowed);
    values.push_back(v);
  }
  require(!values.empty(), parameter, text,
          "an empty list; give at least one value: " + allowed);
  return values;
}

void SweepParameters::declare_parameters(dealii::ParameterHandler& prm)
{
  using dealii::Patterns::Anything;
  prm.enter_subsection("Sweep");
  prm.declare_entry("Speeds", "", Anything(),
                    "Mode = speed sweep: the train speeds [km/h], a list \"250, 280, "
                    "320\" or a range \"200 to 400 step 20\". Every pantograph runs at "
                    "the speed; their positions stay as given.");
  prm.declare_entry("Parameter", "", Anything(),
                    "Mode = parameter sweep: the prm entry to vary, with its "
                    "subsections, e.g. Catenary/Contact wire/Tension. Numeric entries "
                    "only (Double or Integer).");
  prm.declare_entry("Values", "", Anything(),
                    "The values of Parameter: a list or a range \"first to last step "
                    "s\".");
  prm.declare_entry("Second parameter", "", Anything(),
                    "Optional second entry: every value of Parameter runs with every "
                    "value of the second one (a grid).");
  prm.declare_entry("Second values", "", Anything(),
                    "The values of Second parameter: a list or a range.");
  prm.declare_entry("Samples", "0", dealii::Patterns::Integer(),
                    "Mode = monte carlo: the number of samples (> 0).");
  prm.declare_entry("Seed", "1", dealii::Patterns::Integer(0),
                    "Sample i draws its deviations from std::mt19937_64(Seed + i): "
                    "the same seed gives the same samples on any number of ranks.");
  prm.declare_entry("Distribution", "uniform",
                    dealii::Patterns::Selection("uniform|normal"),
                    "uniform: each deviation uniform in [-tolerance, tolerance]; normal: "
                    "mean 0, standard deviation tolerance / 3.");
  prm.declare_entry("Dropper length tolerance", "0", dealii::Patterns::Double(0.),
                    "Installation tolerance of every dropper's length [m] (cut and "
                    "fitted length against the design).");
  prm.declare_entry("Steady arm height tolerance", "0", dealii::Patterns::Double(0.),
                    "Height tolerance of every steady arm's fixing [m].");
  prm.declare_entry("Tension tolerance", "0", dealii::Patterns::Double(0., 0.5),
                    "Relative tolerance of the tension of each wire (0.02: +/- 2 %); 0: "
                    "tensions as designed.");
  prm.declare_entry("Resume", "false", dealii::Patterns::Bool(),
                    "Go on with a sweep that was stopped: the runs in <name>.csv.partial "
                    "of the output directory are kept and not run again. Only a partial "
                    "file of the same program version and parameters, undamaged but for "
                    "the run a stop cut short, is accepted.");
  prm.declare_entry("Stop after runs", "0", dealii::Patterns::Integer(0),
                    "For tests: stop the sweep after this many runs as if it were "
                    "killed (the partial file stays, exit 1); 0: never.");
  prm.declare_entry("Output name", "", Anything(),
                    "Base name of the tables and plots: 1 to 64 letters, digits, '-', "
                    "'_' and '.', not starting with '.' or '-'; empty: speed_sweep, "
                    "parameter_sweep or monte_carlo.");
  prm.leave_subsection();
}

void SweepParameters::parse_parameters(dealii::ParameterHandler& prm,
                                       const std::string& mode)
{
  prm.enter_subsection("Sweep");
  speeds_text = prm.get("Speeds");
  const std::string first = dealii::Utilities::trim(prm.get("Parameter"));
  const std::string second = dealii::Utilities::trim(prm.get("Second parameter"));
  const std::string first_values = prm.get("Values");
  const std::string second_values = prm.get("Second values");
  const long n_samples = prm.get_integer("Samples");
  seed = static_cast<std::uint64_t>(prm.get_integer("Seed"));
  distribution = prm.get("Distribution") == "normal" ? DeviationDistribution::normal
                                                     : DeviationDistribution::uniform;
  dropper_length_tolerance = prm.get_double("Dropper length tolerance");
  steady_arm_height_tolerance = prm.get_double("Steady arm height tolerance");
  tension_tolerance = prm.get_double("Tension tolerance");
  resume = prm.get_bool("Resume");
  stop_after_runs = static_cast<unsigned int>(prm.get_integer("Stop after runs"));
  output_name = prm.get("Output name");
  prm.leave_subsection();

  require_output_name("Sweep/Output name", output_name);
  entries.clear(), values.clear(), values_text.clear(), speeds_kmh.clear();
  if (mode == "speed sweep")
  {
    speeds_kmh = parse_sweep_values(speeds_text, "Sweep/Speeds");
    for (const double v : speeds_kmh)
      require(v > 0., "Sweep/Speeds", speeds_text, "every speed must be > 0 km/h");
    require_distinct_speeds(speeds_kmh, speeds_text);
  }
  if (mode == "parameter sweep")
  {
    require(!first.empty(), "Sweep/Parameter", first,
            "name the prm entry to vary, e.g. Catenary/Contact wire/Tension");
    entries.push_back(first);
    values.push_back(value_words(first_values, "Sweep/Values"));
    values_text.push_back(first_values);
    require_distinct_values(values.back(), "Sweep/Values", first_values);
    if (!second.empty())
    {
      require(second != first, "Sweep/Second parameter", second,
              "must differ from Sweep/Parameter");
      entries.push_back(second);
      values.push_back(value_words(second_values, "Sweep/Second values"));
      values_text.push_back(second_values);
      require_distinct_values(values.back(), "Sweep/Second values", second_values);
    }
    else
      require(dealii::Utilities::trim(second_values).empty(), "Sweep/Second values",
              second_values, "only with a Sweep/Second parameter");
  }
  if (mode == "monte carlo")
  {
    require(n_samples > 0 && n_samples <= 1000000, "Sweep/Samples", n_samples,
            "a Monte Carlo study needs 1 to 1000000 samples");
    samples = static_cast<unsigned int>(n_samples);
    require(dropper_length_tolerance > 0. || steady_arm_height_tolerance > 0. ||
                tension_tolerance > 0.,
            "Sweep/Dropper length tolerance", dropper_length_tolerance,
            "with Steady arm height tolerance and Tension tolerance also 0 every "
            "sample is the designed catenary; set at least one tolerance > 0");
  }
}
} // namespace pantocat
