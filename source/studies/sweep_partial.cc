#include <pantocat/base/input_error.h>
#include <pantocat/studies/sweep_partial.h>

#include <boost/crc.hpp>

#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <sstream>
#include <vector>

#ifndef PANTOCAT_VERSION
#error "PANTOCAT_VERSION (the project's version) is set by CMakeLists.txt"
#endif

namespace pantocat
{
namespace
{
const std::string parameter_prefix = "# set ";
const std::string end_prefix = "# end of run: ";

/// The first line of a partial file of pantocat-fem @p version.
std::string version_line(const std::string& version)
{
  return "# pantocat-fem " + version +
         ": partial results of a sweep (Sweep/Resume = true goes on from here)";
}

/// A refusal of @p file: "Sweep/Resume = true: <file><where>: <what>; allowed: ...".
InputError refused(const std::string& file, const std::string& what,
                   const unsigned int line = 0)
{
  return InputError(
      "Sweep/Resume = true: " + file +
      (line > 0 ? ", line " + std::to_string(line) : std::string()) + ": " + what +
      "; allowed: the partial file of this sweep as a stopped run left it, or remove "
      "it (Resume = false starts the sweep afresh and replaces it), or another output "
      "directory");
}

/// The line that closes the record of @p rows.
std::string end_line(const std::string& rows, const unsigned int n_rows)
{
  boost::crc_32_type crc;
  crc.process_bytes(rows.data(), rows.size());
  std::ostringstream line;
  line << end_prefix << n_rows << (n_rows == 1 ? " row" : " rows") << ", CRC-32 "
       << std::hex << std::setw(8) << std::setfill('0') << crc.checksum();
  return line.str();
}

/// The fields of CSV line @p line (quotes as RFC 4180), and which were quoted; false if
/// a quote is broken.
bool split_csv(const std::string& line, std::vector<std::string>& fields,
               std::vector<bool>& quoted)
{
  fields.assign(1, ""), quoted.assign(1, false);
  bool inside = false;
  for (std::size_t i = 0; i < line.size(); ++i)
  {
    const char c = line[i];
    if (inside && c == '"' && i + 1 < line.size() && line[i + 1] == '"')
      fields.back() += '"', ++i;
    else if (inside && c == '"')
    {
      inside = false;
      if (i + 1 < line.size() && line[i + 1] != ',')
        return false; // text after a closing quote
    }
    else if (inside)
      fields.back() += c;
    else if (c == ',')
      fields.emplace_back(), quoted.push_back(false);
    else if (c == '"' && fields.back().empty() && !quoted.back())
      inside = true, quoted.back() = true;
    else if (c == '"')
      return false; // a quote inside an unquoted field
    else
      fields.back() += c;
  }
  return !inside;
}

/// True if @p text is a finite number and nothing else.
bool is_finite_number(const std::string& text)
{
  if (text.empty() || std::isspace(static_cast<unsigned char>(text.front())))
    return false;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(value);
}

/// One row of a partial file, checked field by field.
struct PartialRow
{
  std::vector<std::string> key;
  unsigned int pantograph = 0;
  std::string status;
};

/**
 * Row @p line of a sweep with @p n_keys key columns, or the reason it is no
 * row this program writes ("" in @p error if it is one).
 */
PartialRow parse_row(const std::string& line, const std::size_t n_keys,
                     std::string& error)
{
  PartialRow row;
  std::vector<std::string> f;
  std::vector<bool> quoted;
  const std::vector<std::string>& figures = sweep_statistic_columns();
  const std::size_t n_fields = n_keys + 3 + figures.size();
  if (!split_csv(line, f, quoted))
    return error = "a broken quote", row;
  if (f.size() != n_fields)
    return error = std::to_string(f.size()) + (f.size() == 1 ? " field" : " fields") +
                   ", a row has " + std::to_string(n_fields) +
                   " (the key columns, pantograph, 15 figures, status, reason)",
           row;
  row.key.assign(f.begin(), f.begin() + n_keys);
  const std::string& p = f[n_keys];
  const bool digits = !p.empty() && p.size() < 6 && p[0] != '0' &&
                      p.find_first_not_of("0123456789") == std::string::npos;
  if (!digits)
    return error = "pantograph \"" + p + "\" is not a pantograph number", row;
  row.pantograph = static_cast<unsigned int>(std::stoul(p));
  row.status = f[n_fields - 2];
  const bool completed = row.status == "completed";
  if (!completed && row.status != "failed" && row.status != "refused")
    return error = "status \"" + row.status + "\" is not completed, failed or refused",
           row;
  for (std::size_t c = 0; c < figures.size(); ++c)
  {
    const std::string& x = f[n_keys + 1 + c];
    if (!completed && !x.empty())
      return error = figures[c] + " = " + x + " in a run that " + row.status +
                     " (which has no figures)",
             row;
    if (completed && !x.empty() && !is_finite_number(x))
      return error = figures[c] + " = \"" + x + "\" is not a finite number", row;
  }
  const std::string& reason = f[n_fields - 1];
  if (!quoted[n_fields - 1] || completed != reason.empty())
    return error = completed ? "a completed run with a reason, or an unquoted one"
                             : "a run that " + row.status + " without a quoted reason",
           row;
  return row;
}

/// "speed_kmh = 250" for run @p key of @p plan.
std::string run_name(const SweepPlan& plan, const std::vector<std::string>& key)
{
  std::string name;
  for (std::size_t c = 0; c < key.size() && c < plan.key_columns.size(); ++c)
    name += (c ? ", " : "") + plan.key_columns[c] + " = " + key[c];
  return name;
}

/// The lines of @p text; @p torn is set if the last one has no newline.
std::vector<std::string> lines_of(const std::string& text, bool& torn)
{
  std::vector<std::string> lines;
  std::size_t begin = 0;
  while (begin < text.size())
  {
    const std::size_t end = text.find('\n', begin);
    if (end == std::string::npos)
      break;
    lines.push_back(text.substr(begin, end - begin));
    begin = end + 1;
  }
  torn = begin < text.size();
  return lines;
}

/// The first difference of the parameters a partial file was written with, or "".
std::string parameter_difference(const ParameterFingerprint& there,
                                 const ParameterFingerprint& here)
{
  std::map<std::string, std::string> old(there.begin(), there.end());
  std::map<std::string, std::string> now(here.begin(), here.end());
  std::string first;
  unsigned int n = 0;
  for (const auto& [name, value] : now)
  {
    const auto o = old.find(name);
    const std::string was = o == old.end() ? "(not set)" : o->second;
    if (was != value && n++ == 0)
      first = name + " = " + was + " there, " + value + " in this sweep";
  }
  for (const auto& [name, value] : old)
    if (now.count(name) == 0 && n++ == 0)
      first = name + " = " + value + " there, which this sweep does not have";
  if (n > 1)
    first += " (and " + std::to_string(n - 1) + " more " +
             (n == 2 ? "entry differs" : "entries differ") + ")";
  return first;
}

/**
 * Checks the start of a partial file (version, parameters, header) at
 * @p lines; returns the index of the first line after the header.
 */
std::size_t check_start(const std::vector<std::string>& lines, const std::string& file,
                        const SweepPlan& plan)
{
  const std::string head = "# pantocat-fem ";
  const std::string& first = lines.empty() ? std::string() : lines[0];
  const std::size_t colon = first.find(':');
  if (first.rfind(head, 0) != 0 || colon == std::string::npos ||
      first != version_line(first.substr(head.size(), colon - head.size())))
    throw refused(file, "not a partial file of pantocat-fem " + program_version() +
                            " (its first line is not \"" +
                            version_line(program_version()) + "\")");
  const std::string version = first.substr(head.size(), colon - head.size());
  if (version != program_version())
    throw refused(file, "written by pantocat-fem " + version + ", this is " +
                            program_version() + ", whose rows may differ");
  ParameterFingerprint there;
  std::size_t i = 1;
  for (; i < lines.size() && lines[i].rfind(parameter_prefix, 0) == 0; ++i)
  {
    const std::size_t eq = lines[i].find(" = ", parameter_prefix.size());
    if (eq == std::string::npos)
      throw refused(file, "a parameter line without \" = \"", i + 1);
    there.emplace_back(
        lines[i].substr(parameter_prefix.size(), eq - parameter_prefix.size()),
        lines[i].substr(eq + 3));
  }
  const std::string difference = parameter_difference(there, plan.parameters);
  if (!difference.empty())
    throw refused(file, "written by a sweep with other parameters: " + difference);
  if (i >= lines.size() || lines[i] + "\n" != sweep_csv_header(plan.key_columns))
    throw refused(file,
                  "not the columns of this sweep (another mode or other swept entries)",
                  i + 1);
  return i + 1;
}

/// Reads the records of a partial file line by line: rows, then their end line.
class RecordReader
{
public:
  RecordReader(const SweepPlan& plan, const std::string& file) : plan(plan), file(file)
  {
    for (unsigned int k = 0; k < plan.size(); ++k)
      index[plan.keys[k]] = k;
  }

  /// Row @p line (line @p number of the file) of the run being read.
  void row(const std::string& line, const unsigned int number)
  {
    std::string error;
    const PartialRow r = parse_row(line, plan.key_columns.size(), error);
    if (!error.empty())
      throw refused(file, error, number);
    const auto k = index.find(r.key);
    if (k == index.end())
      throw refused(file,
                    "a run (" + run_name(plan, r.key) + ") that this sweep does not have",
                    number);
    if (n_rows == 0)
    {
      const auto earlier = ended_on.find(k->second);
      if (earlier != ended_on.end())
        throw refused(file,
                      "a second record of the run " + run_name(plan, r.key) +
                          " (its first ends on line " + std::to_string(earlier->second) +
                          ")",
                      number);
      run = k->second, status = r.status, last_pantograph = 0;
    }
    else if (k->second != run)
      throw refused(file,
                    "a row of the run " + run_name(plan, r.key) +
                        " inside the record of the run " +
                        run_name(plan, plan.keys[run]) + ", whose end line is missing",
                    number);
    check_row(r, number);
    rows += line + "\n", ++n_rows, last_pantograph = r.pantograph;
  }

  /// The end line @p line (line @p number) of the run being read.
  void end(const std::string& line, const unsigned int number)
  {
    if (n_rows == 0)
      throw refused(file, "an end line without the rows of a run", number);
    if (line != end_line(rows, n_rows))
      throw refused(
          file,
          "the end line does not match the " +
              (n_rows == 1 ? std::string("row") : std::to_string(n_rows) + " rows") +
              " above it (\"" + end_line(rows, n_rows) +
              "\" expected): they were changed after they were written",
          number);
    if (n_rows != expected_rows(run))
      throw refused(file,
                    "the run " + run_name(plan, plan.keys[run]) + " has " +
                        std::to_string(n_rows) + " rows, one per pantograph is " +
                        std::to_string(expected_rows(run)),
                    number);
    result.rows[run] = rows;
    ended_on[run] = number;
    rows.clear(), n_rows = 0;
  }

  /// The finished runs; the rows of an unfinished last record and a torn line dropped.
  PartialRuns finish(const bool torn)
  {
    result.dropped_lines = n_rows + (torn ? 1 : 0);
    return result;
  }

private:
  unsigned int expected_rows(const unsigned int k) const
  {
    return std::max(plan.pantographs[k], 1u);
  }

  /// Row @p r against the rows of its run before it.
  void check_row(const PartialRow& r, const unsigned int number) const
  {
    if (r.status != status)
      throw refused(file,
                    "status " + r.status + " in a run whose first row says " + status,
                    number);
    if (n_rows >= expected_rows(run))
      throw refused(file,
                    "a row more than the " + std::to_string(expected_rows(run)) +
                        " of the run " + run_name(plan, r.key) + " (one per pantograph)",
                    number);
    if (r.pantograph <= last_pantograph)
      throw refused(file,
                    "pantograph " + std::to_string(r.pantograph) + " after pantograph " +
                        std::to_string(last_pantograph) +
                        " (a run has one row per pantograph, in increasing order)",
                    number);
    if (status != "completed" && r.pantograph != n_rows + 1)
      throw refused(file,
                    "pantograph " + std::to_string(r.pantograph) + " as row " +
                        std::to_string(n_rows + 1) + " of a run that " + status,
                    number);
  }

  const SweepPlan& plan;
  const std::string& file;
  std::map<std::vector<std::string>, unsigned int> index;
  std::map<unsigned int, unsigned int> ended_on; ///< run -> line of its end line
  PartialRuns result;
  // The record being read.
  std::string rows, status;
  unsigned int n_rows = 0, run = 0, last_pantograph = 0;
};
} // namespace

const std::string& program_version()
{
  static const std::string version = PANTOCAT_VERSION;
  return version;
}

std::string partial_file_start(const SweepPlan& plan)
{
  std::string text = version_line(program_version()) + "\n";
  for (const auto& [name, value] : plan.parameters)
    text += parameter_prefix + name + " = " + value + "\n";
  return text + sweep_csv_header(plan.key_columns);
}

std::string partial_record(const std::string& rows)
{
  unsigned int n = 0;
  for (const char c : rows)
    n += c == '\n' ? 1 : 0;
  return rows + end_line(rows, n) + "\n";
}

PartialRuns read_partial_file(const std::string& text, const std::string& file,
                              const SweepPlan& plan)
{
  bool torn = false;
  const std::vector<std::string> lines = lines_of(text, torn);
  RecordReader reader(plan, file);
  for (std::size_t i = check_start(lines, file, plan); i < lines.size(); ++i)
    if (lines[i].rfind(end_prefix, 0) == 0)
      reader.end(lines[i], i + 1);
    else
      reader.row(lines[i], i + 1);
  return reader.finish(torn);
}
} // namespace pantocat
