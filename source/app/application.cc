#include <pantocat/app/application.h>
#include <pantocat/app/command_line.h>
#include <pantocat/app/parameter_input.h>
#include <pantocat/app/program_parameters.h>
#include <pantocat/app/run_modes.h>
#include <pantocat/base/input_error.h>
#include <pantocat/studies/convergence_study.h>
#include <pantocat/studies/work_precision_study.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/parameter_handler.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>

namespace pantocat
{
namespace
{
void print_parameters(const std::string& format)
{
  dealii::ParameterHandler prm;
  ProgramParameters::declare_parameters(prm);
  prm.print_parameters(std::cout, format == "json" ? dealii::ParameterHandler::JSON
                                                   : dealii::ParameterHandler::PRM);
}

/**
 * Creates the output directory and writes the fully resolved parameters into
 * it. discard() removes what it wrote (and the directory, if it made it and
 * nothing else is in it): for a run stopped by bad input, so that nothing is
 * left that looks like a result.
 */
class OutputDirectory
{
public:
  OutputDirectory(const dealii::ParameterHandler& prm, const std::string& dir)
      : parameters(std::filesystem::path(dir) / "parameters.prm")
  {
    std::error_code error;
    created = std::filesystem::create_directories(dir, error);
    std::ofstream out(parameters);
    if (error || !out)
      throw InputError("Output/Output directory = " + dir +
                       ": cannot create or write to this directory");
    prm.print_parameters(out, dealii::ParameterHandler::PRM);
  }
  void discard() const
  {
    std::error_code ignored;
    std::filesystem::remove(parameters, ignored);
    if (created && std::filesystem::is_empty(parameters.parent_path(), ignored))
      std::filesystem::remove(parameters.parent_path(), ignored);
  }

private:
  std::filesystem::path parameters;
  bool created = false;
};

/// True when started by an MPI launcher (mpirun sets one of these).
bool launched_by_mpi()
{
  for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(variable) != nullptr)
      return true;
  return false;
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
  // A serial run uses no MPI or Trilinos object: skip MPI's start-up (about
  // 0.35 s) unless an MPI launcher started us or Trilinos solves (its
  // matrices need MPI).
  std::optional<dealii::Utilities::MPI::MPI_InitFinalize> mpi;
  const auto& ti = parameters.time_integration;
  if (launched_by_mpi() || ti.linear_solver == LinearSolverType::trilinos_klu ||
      (ti.integrator == "ida" && ti.ida_linear_solver == "trilinos-klu"))
    mpi.emplace(argc, argv, 1);
  // One thread: vectors of a few thousand entries lose more to TBB's
  // scheduling than they gain.
  dealii::MultithreadInfo::set_thread_limit(1);
  const OutputDirectory output(prm, parameters.output.directory);
  // Verbosity = quiet: the screen output goes nowhere (errors go to stderr).
  std::ostream discard(nullptr);
  std::ostream& out =
      parameters.output.verbosity == Verbosity::quiet ? discard : std::cout;
  try
  {
    switch (parameters.mode)
    {
    case RunMode::eigenfrequencies:
      run_eigenfrequencies(parameters, out);
      break;
    case RunMode::static_equilibrium:
      run_static_equilibrium(parameters, out);
      break;
    case RunMode::dynamics:
      run_dynamics(parameters, out);
      break;
    case RunMode::convergence_study:
      run_convergence_study(parameters.make_study_case(), std::cout);
      break;
    case RunMode::work_precision:
      run_work_precision_study(parameters.make_study_case(), std::cout);
      break;
    }
  }
  catch (const InputError&)
  {
    output.discard(); // a failed simulation keeps its outputs, marked failed
    throw;
  }
  return 0;
}
} // namespace

int run_application(int argc, char** argv)
{
  try
  {
    return run(CommandLine::parse(argc, argv), argc, argv);
  }
  catch (const InputError& e)
  {
    std::cerr << "pantocat-fem: error: " << e.what() << std::endl;
    return 2;
  }
  catch (const SimulationError& e)
  {
    std::cerr << "pantocat-fem: simulation failed: " << e.what() << std::endl;
    return 1;
  }
  catch (const std::exception& e)
  {
    std::cerr << "pantocat-fem: error: " << one_line_message(e) << std::endl;
    return 1;
  }
}
} // namespace pantocat
