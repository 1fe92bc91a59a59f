#include <pantocat/app/application.h>
#include <pantocat/app/command_line.h>
#include <pantocat/app/input_warnings.h>
#include <pantocat/app/parameter_input.h>
#include <pantocat/app/program_parameters.h>
#include <pantocat/app/run_modes.h>
#include <pantocat/app/run_phase.h>
#include <pantocat/app/sweep_mode.h>
#include <pantocat/base/input_error.h>
#include <pantocat/base/safe_files.h>
#include <pantocat/studies/convergence_study.h>
#include <pantocat/studies/work_precision_study.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/parameter_handler.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <regex>
#include <sstream>
#include <streambuf>
#include <vector>

namespace pantocat
{
namespace
{
void print_parameters(const std::string& format)
{
  dealii::ParameterHandler prm;
  ProgramParameters::declare_parameters(prm);
  std::cout << printed_parameters(prm, format == "json" ? dealii::ParameterHandler::JSON
                                                        : dealii::ParameterHandler::PRM);
}

/// The whole content of @p file, if it is a regular file (not a link) of at most 16 MiB.
std::optional<std::string> content_of(const std::filesystem::path& file)
{
  return read_regular_file(file.string(), std::uint64_t(16) << 20, false).bytes;
}

/// write_file_atomically(), false instead of an exception.
bool write_atomically(const std::filesystem::path& file, const std::string& text)
{
  try
  {
    write_file_atomically(file.string(), text);
    return true;
  }
  catch (const SimulationError&)
  {
    return false;
  }
}

/**
 * Creates the output directory, locks it for this run (DirectoryLock: a
 * second run into a busy directory is refused before it touches anything)
 * and writes the fully resolved parameters into it. discard() undoes that
 * for a run stopped by bad input, so that nothing is left that looks like a
 * result: it removes parameters.prm (and the directory, if it made it and
 * nothing else is in it), or puts back the parameters.prm that was there
 * before. That may be the input file itself (`pantocat-fem
 * out/parameters.prm`), read before this object is made: a refusal leaves it
 * as it was.
 */
class OutputDirectory
{
public:
  OutputDirectory(const dealii::ParameterHandler& prm, const std::string& dir)
      : parameters(std::filesystem::path(dir) / "parameters.prm")
  {
    const std::string what = "Output/Output directory = " + dir + ": ";
    std::error_code error;
    created = std::filesystem::create_directories(dir, error);
    if (error || !std::filesystem::is_directory(dir, error))
      throw InputError(what + "cannot create this directory" +
                       (error ? " (" + error.message() + ")" : ""));
    lock_directory(what, dir);
    for (const std::string& name : result_files())
      if (std::filesystem::is_directory(std::filesystem::path(dir) / name, error))
        throw InputError(what + (std::filesystem::path(dir) / name).string() +
                         " is a directory; a run writes a file of that name there");
    previous = content_of(parameters);
    try
    {
      write_file_atomically(parameters.string(),
                            printed_parameters(prm, dealii::ParameterHandler::PRM));
    }
    catch (const SimulationError& e)
    {
      discard();
      throw InputError(what + e.what());
    }
  }
  void discard()
  {
    std::error_code ignored;
    if (previous)
      write_atomically(parameters, *previous);
    else
      std::filesystem::remove(parameters, ignored);
    if (lock && lock->made_file())
      lock->remove(); // the directory is left as it was
    if (created && std::filesystem::is_empty(parameters.parent_path(), ignored))
      std::filesystem::remove(parameters.parent_path(), ignored);
  }

private:
  /// Takes the directory's lock; an InputError if another run holds it.
  void lock_directory(const std::string& what, const std::string& dir)
  {
    try
    {
      lock.emplace(dir);
    }
    catch (const SimulationError& e)
    {
      throw InputError(what + e.what());
    }
    if (!lock->locked())
    {
      const std::string pid = lock->holder();
      throw InputError(what + "another run" +
                       (pid.empty() ? "" : " (process " + pid + ")") +
                       " is writing into this directory; wait until it ends or choose "
                       "another directory");
    }
  }

  std::filesystem::path parameters;
  std::optional<DirectoryLock> lock;   ///< held while the run lasts
  std::optional<std::string> previous; ///< parameters.prm before this run
  bool created = false;
};

/**
 * Makes @p output in the process that writes (rank 0 of a study under MPI;
 * its refusal stops every rank), none on the others.
 */
void make_output_directory(std::optional<OutputDirectory>& output,
                           const dealii::ParameterHandler& prm, const std::string& dir,
                           const bool writes, const bool mpi)
{
  std::string refusal;
  try
  {
    if (writes)
      output.emplace(prm, dir);
  }
  catch (const InputError& e)
  {
    refusal = e.what();
  }
  if (mpi && dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1)
    refusal = dealii::Utilities::MPI::broadcast(MPI_COMM_WORLD, refusal, 0);
  if (!refusal.empty())
    throw InputError(refusal);
}

/**
 * Holds back the warnings written to a stream (std::cerr): lines that start
 * with "pantocat-fem: warning:" and deal.II's notes on a deprecated entry
 * name ("Warning in line <n> ..."), and passes everything else through as it
 * comes (the progress line included). A run refused for bad input prints
 * exactly one line, its error, so the warnings of a refused run are dropped;
 * otherwise release() prints them, at the end, each once, deal.II's in our
 * words.
 */
class WarningHold : public std::streambuf
{
public:
  explicit WarningHold(std::ostream& stream) : stream(stream), target(stream.rdbuf())
  {
    stream.rdbuf(this);
  }
  ~WarningHold() override { restore(); }
  WarningHold(const WarningHold&) = delete;
  WarningHold& operator=(const WarningHold&) = delete;

  /// Gives the stream its own buffer back; the held warnings stay here.
  void restore()
  {
    if (stream.rdbuf() != this)
      return;
    if (mode != Mode::holding)
      target->sputn(line.data(), line.size()); // an unfinished line that is no warning
    line.clear();
    stream.rdbuf(target);
  }
  /// Prints the held warnings to the stream, each once.
  void release()
  {
    restore();
    std::istringstream lines(held);
    std::vector<std::string> printed;
    for (std::string line; std::getline(lines, line);)
    {
      line = in_our_words(line);
      if (std::find(printed.begin(), printed.end(), line) == printed.end())
        stream << line << '\n', printed.push_back(line);
    }
    stream << std::flush;
    held.clear();
  }

protected:
  int_type overflow(const int_type c) override
  {
    if (!traits_type::eq_int_type(c, traits_type::eof()))
      put(traits_type::to_char_type(c));
    return traits_type::not_eof(c);
  }
  std::streamsize xsputn(const char* s, const std::streamsize n) override
  {
    for (std::streamsize i = 0; i < n; ++i)
      put(s[i]);
    return n;
  }
  int sync() override { return mode == Mode::passing ? target->pubsync() : 0; }

private:
  enum class Mode
  {
    deciding, ///< at the start of a line, which may still become a warning
    holding,  ///< in a warning line
    passing   ///< in any other line
  };

  void put(const char c)
  {
    if (mode == Mode::holding)
      held += c;
    else if (mode == Mode::passing)
      target->sputc(c);
    else
    {
      line += c;
      const auto starts = [&](const std::string& m)
      { return m.compare(0, line.size(), line) == 0; };
      if (line == markers[0] || line == markers[1])
        mode = Mode::holding, held += line, line.clear();
      else if (!starts(markers[0]) && !starts(markers[1]))
        mode = Mode::passing, target->sputn(line.data(), line.size()), line.clear();
    }
    if ((c == '\n' || c == '\r') && mode != Mode::deciding)
      mode = Mode::deciding;
  }

  /// deal.II's note on a deprecated name (declare_alias()) as our warning.
  static std::string in_our_words(const std::string& line)
  {
    static const std::regex deprecated(
        "Warning in line <([0-9]+)> of file <([^>]*)>: You are using the deprecated "
        "spelling <([^>]*)> of the parameter <([^>]*)>\\.?");
    std::smatch m;
    if (!std::regex_match(line, m, deprecated))
      return line;
    const bool command_line = m[2].str().empty() || m[2].str() == "input string";
    return "pantocat-fem: warning: " + (command_line ? "--set" : m[2].str()) +
           (command_line ? "" : ", line " + m[1].str()) + ": '" + m[3].str() +
           "' is the old name of '" + m[4].str() + "' (accepted; use the new name)";
  }

  const std::string markers[2] = {"pantocat-fem: warning:", "Warning in line <"};
  std::ostream& stream;
  std::streambuf* target;
  Mode mode = Mode::deciding;
  std::string line, held;
};

/// True when started by an MPI launcher (mpirun sets one of these).
bool launched_by_mpi()
{
  for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(variable) != nullptr)
      return true;
  return false;
}

/**
 * This process's rank as the MPI launcher announces it (0 without one). Known
 * before MPI starts, so that only rank 0 prints the error of bad input, which
 * every rank finds.
 */
unsigned int launcher_rank()
{
  for (const char* variable : {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"})
    if (const char* value = std::getenv(variable))
      return static_cast<unsigned int>(std::strtoul(value, nullptr, 10));
  return 0;
}

void run_mode(const ProgramParameters& parameters, const dealii::ParameterHandler& prm,
              const SweepInput& input, std::ostream& out, RunPhase& phase)
{
  switch (parameters.mode)
  {
  case RunMode::eigenfrequencies:
    run_eigenfrequencies(parameters, out, phase);
    break;
  case RunMode::static_equilibrium:
    run_static_equilibrium(parameters, out, phase);
    break;
  case RunMode::dynamics:
    run_dynamics(parameters, out, phase);
    break;
  case RunMode::convergence_study:
    phase.begin_study();
    run_convergence_study(parameters.make_study_case(), std::cout);
    break;
  case RunMode::work_precision:
    phase.begin_study();
    run_work_precision_study(parameters.make_study_case(), std::cout);
    break;
  case RunMode::speed_sweep:
  case RunMode::parameter_sweep:
  case RunMode::monte_carlo:
    phase.begin_study();
    run_sweep(parameters, prm, input, out);
    break;
  }
}

int run(const CommandLine& cl, int argc, char** argv)
{
  if (cl.help)
  {
    std::cout << CommandLine::usage();
    return 0;
  }
  if (cl.print_parameters)
  {
    print_parameters(*cl.print_parameters);
    return 0;
  }
  dealii::ParameterHandler prm;
  std::vector<std::string> overrides = cl.overrides;
  if (cl.output_directory)
    overrides.push_back("Output/Output directory=" + *cl.output_directory);
  read_program_parameters(prm, cl.parameter_file, overrides);

  ProgramParameters parameters;
  parameters.parse_parameters(prm);
  {
    dealii::ParameterHandler defaults;
    ProgramParameters::declare_parameters(defaults, parameters.scene.pantographs.size(),
                                          parameters.scene.pantographs[0]);
    parameters.inputs = entries_set(prm, defaults);
    warn_about_unused_entries(parameters.inputs, parameters, std::cerr);
  }
  // A serial run uses no MPI or Trilinos object: skip MPI's start-up (about
  // 0.35 s) unless an MPI launcher started us or Trilinos solves (its
  // matrices need MPI).
  std::optional<dealii::Utilities::MPI::MPI_InitFinalize> mpi;
  const auto& ti = parameters.time_integration;
  if (launched_by_mpi() || ti.linear_solver == LinearSolverType::trilinos_klu ||
      (ti.integrator == "ida" && ti.ida_linear_solver == "trilinos-klu"))
    mpi.emplace(argc, argv, 1);
  // Only the studies spread their runs over MPI ranks. Any other mode under
  // mpirun runs once, on rank 0; the other ranks (which had to start MPI
  // with it) leave at once, silently, with status 0.
  if (mpi && !is_study(parameters.mode) &&
      dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
    return 0;
  // One thread: vectors of a few thousand entries lose more to TBB's
  // scheduling than they gain.
  dealii::MultithreadInfo::set_thread_limit(1);
  // Studies write from rank 0 (their runs are spread over the ranks).
  const bool writes =
      !mpi || dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  std::optional<OutputDirectory> output;
  make_output_directory(output, prm, parameters.output.directory, writes,
                        mpi.has_value());
  // Verbosity = quiet: the screen output goes nowhere (errors go to stderr).
  std::ostream discard(nullptr);
  std::ostream& out =
      parameters.output.verbosity == Verbosity::quiet ? discard : std::cout;
  RunPhase phase(parameters.output.directory,
                 parameters.mode == RunMode::dynamics && parameters.checkpoint.resume);
  try
  {
    run_mode(parameters, prm, {cl.parameter_file, overrides}, out, phase);
  }
  catch (const InputError&)
  {
    if (output)
    {
      phase.refused();
      output->discard(); // a refusal leaves the directory as it was
    }
    throw;
  }
  catch (const std::exception& e)
  {
    if (writes) // a failed run keeps its outputs, marked failed
      try
      {
        phase.fail(dynamic_cast<const SimulationError*>(&e) ? e.what()
                                                            : one_line_message(e));
      }
      catch (const std::exception&)
      {
        // The summary cannot be written either (a full disk): the error line
        // names the file whose failure stopped the run.
      }
    throw;
  }
  return 0;
}

/**
 * "cannot remove out/summary.json: Directory not empty" from a filesystem
 * error, whose what() is "filesystem error: cannot remove: ... [path]".
 */
std::string filesystem_failure(const std::filesystem::filesystem_error& e)
{
  const std::string what = e.what();
  const auto begin = what.find("cannot ");
  const auto end = what.find(':', begin);
  const std::string operation = begin != std::string::npos && end != std::string::npos
                                    ? what.substr(begin, end - begin)
                                    : "file system operation failed on";
  return operation + " " + e.path1().string() + ": " + e.code().message();
}

/// The error line of an exception that ends the program, and its exit status.
std::pair<int, std::string> error_line(const std::exception_ptr& error)
{
  try
  {
    std::rethrow_exception(error);
  }
  catch (const InputError& e)
  {
    return {2, std::string("error: ") + e.what()};
  }
  catch (const SimulationError& e)
  {
    return {1, std::string("simulation failed: ") + e.what()};
  }
  catch (const std::filesystem::filesystem_error& e)
  {
    return {1, "error: " + filesystem_failure(e)};
  }
  catch (const std::bad_alloc&)
  {
    return {1, "error: out of memory"};
  }
  catch (const std::exception& e)
  {
    return {1, "error: " + one_line_message(e)};
  }
}
} // namespace

int run_application(int argc, char** argv)
{
  WarningHold warnings(std::cerr);
  std::exception_ptr error;
  try
  {
    const int status = run(CommandLine::parse(argc, argv), argc, argv);
    warnings.release();
    return status;
  }
  catch (...)
  {
    error = std::current_exception();
  }
  const auto [status, line] = error_line(error);
  // Bad input: exactly one line, the error (no warnings before it); under
  // mpirun, every rank finds it and rank 0 says it.
  if (status == 2)
    warnings.restore();
  else
    warnings.release();
  if (launcher_rank() == 0)
    std::cerr << "pantocat-fem: " << printable_line(line) << std::endl;
  return status;
}
} // namespace pantocat
