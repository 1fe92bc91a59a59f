#include <pantocat/base/input_error.h>
#include <pantocat/io/atomic_file.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace pantocat
{
void write_file_atomically(const std::string& file, const std::string& content)
{
  // The process id keeps ranks that write the same file (parameters.prm of
  // a study under mpirun) off each other's temporary file.
  const std::string temporary = file + ".tmp" + std::to_string(getpid());
  bool written = false;
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.flush();
    written = static_cast<bool>(out);
  }
  const std::string reason = errno != 0 ? std::strerror(errno) : "write error";
  std::error_code error;
  if (written)
    std::filesystem::rename(temporary, file, error);
  if (!written || error)
  {
    std::filesystem::remove(temporary, error);
    throw SimulationError("cannot write " + file + ": " +
                          (written ? error.message() : reason));
  }
}
} // namespace pantocat
