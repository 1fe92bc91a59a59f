#pragma once

#include <string>
#include <vector>

namespace pantocat
{
/**
 * The absolute path of the executable @p name, looked up in the directories
 * of the environment variable PATH (in order, as a shell does, but without
 * one; empty entries, which a shell reads as the current directory, are
 * skipped). Empty if there is none.
 */
std::string find_program(const std::string& name);

/**
 * Runs the executable @p program (a path) with @p arguments in the working
 * directory @p working_directory and waits for it. No shell is involved: each
 * argument reaches the program as one word, whatever characters it holds
 * (quotes, semicolons, $(...)), and the working directory is set in the child
 * process only. Its standard input, output and error are /dev/null, so that
 * it cannot add lines to the program's own output. Returns true if it ran
 * and exited with status 0.
 */
bool run_program(const std::string& program, const std::vector<std::string>& arguments,
                 const std::string& working_directory);
} // namespace pantocat
