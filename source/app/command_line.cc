#include <pantocat/app/command_line.h>
#include <pantocat/app/parameter_input.h>
#include <pantocat/base/input_error.h>

namespace pantocat
{
namespace
{
/// The formats of --print-parameters (as --help lists them); InputError otherwise.
std::string print_format(const std::string& format)
{
  if (format != "prm" && format != "json")
    throw InputError("--print-parameters " + format +
                     ": unknown format; allowed: prm | json");
  return format;
}

/**
 * The output directory of -o: not with a control character, which would
 * also go into the parameters.prm written there (a newline would start a
 * line of its own when that file is read again).
 */
std::string checked_directory(const std::string& option, const std::string& dir)
{
  if (printable_line(dir) != dir)
    throw InputError(option + " " + printable_line(dir) +
                     ": a directory name with a control character is not allowed");
  return dir;
}
} // namespace

std::string CommandLine::usage()
{
  return "usage: pantocat-fem [options] CASE.prm\n"
         "\n"
         "Pantograph-catenary dynamics after Arnold & Simeon (PDAE approach): FEM/FDM\n"
         "semi-discretisation of the catenary, static equilibrium and eigenfrequencies.\n"
         "\n"
         "options:\n"
         "  -h, --help                      this text\n"
         "  --print-parameters [prm|json]   every parameter with its default and\n"
         "                                  documentation (a template for CASE.prm)\n"
         "  --set \"Subsection/Name=value\"   override an entry of CASE.prm "
         "(repeatable)\n"
         "  -o, --output-directory DIR      override Output/Output directory\n"
         "\n"
         "examples:\n"
         "  pantocat-fem prm/table1.prm\n"
         "  pantocat-fem prm/static.prm --set \"Discretisation/Method=fdm\" -o out-fdm\n";
}

CommandLine CommandLine::parse(const int argc, const char* const* argv)
{
  CommandLine cl;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    const auto value = [&](const std::string& option)
    {
      if (i + 1 >= argc)
        throw InputError(option + ": missing value");
      return std::string(argv[++i]);
    };
    if (arg == "-h" || arg == "--help")
      cl.help = true;
    else if (arg == "--print-parameters")
    {
      // The format is optional; a word that follows must be one of them.
      cl.print_parameters = "prm";
      if (i + 1 < argc && argv[i + 1][0] != '-')
        cl.print_parameters = print_format(argv[++i]);
    }
    else if (arg == "--set")
      cl.overrides.push_back(value(arg));
    else if (arg == "-o" || arg == "--output-directory")
      cl.output_directory = checked_directory(arg, value(arg));
    else if (!arg.empty() && arg[0] == '-')
      throw InputError("unknown option " + arg + " (see pantocat-fem --help)");
    else if (cl.parameter_file.empty())
      cl.parameter_file = arg;
    else
      throw InputError("more than one parameter file given: " + cl.parameter_file +
                       " and " + arg);
  }
  if (!cl.help && !cl.print_parameters && cl.parameter_file.empty())
    throw InputError("no parameter file given (see pantocat-fem --help)");
  return cl;
}
} // namespace pantocat
