#pragma once

namespace pantocat
{
/**
 * The program `pantocat-fem`: parses the command line and the prm file,
 * creates the output directory, writes the resolved parameters.prm into it
 * and runs the selected mode. Returns the exit status: 0 on success, 1 for a
 * failed simulation, 2 for bad input (one line on stderr, nothing written).
 */
int run_application(int argc, char** argv);
} // namespace pantocat
