#pragma once

#include <string>

namespace pantocat
{
/**
 * Writes @p content to @p file as a whole or not at all: into file + ".tmp<pid>",
 * flushed and checked (a full disk is an error, not a cut file), then renamed
 * over @p file (atomic on POSIX). A reader, or a run killed meanwhile, never
 * sees it half written. Throws SimulationError naming the file and the
 * reason; the temporary file is removed then.
 */
void write_file_atomically(const std::string& file, const std::string& content);
} // namespace pantocat
