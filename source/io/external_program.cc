#include <pantocat/io/external_program.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace pantocat
{
namespace
{
/// True if @p path is a regular file that this process may execute.
bool is_executable_file(const std::string& path)
{
  struct stat info;
  return stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode) &&
         access(path.c_str(), X_OK) == 0;
}

/// Owns a posix_spawn_file_actions_t: stdin, stdout, stderr to /dev/null, and
/// the working directory of the child.
class SpawnActions
{
public:
  explicit SpawnActions(const std::string& working_directory)
  {
    ok = posix_spawn_file_actions_init(&actions) == 0;
    initialised = ok;
    ok = ok && posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null",
                                                O_RDONLY, 0) == 0;
    for (const int fd : {STDOUT_FILENO, STDERR_FILENO})
      ok = ok &&
           posix_spawn_file_actions_addopen(&actions, fd, "/dev/null", O_WRONLY, 0) == 0;
    ok = ok &&
         posix_spawn_file_actions_addchdir_np(&actions, working_directory.c_str()) == 0;
  }
  ~SpawnActions()
  {
    if (initialised)
      posix_spawn_file_actions_destroy(&actions);
  }
  SpawnActions(const SpawnActions&) = delete;
  SpawnActions& operator=(const SpawnActions&) = delete;

  bool ok = false;
  posix_spawn_file_actions_t actions;

private:
  bool initialised = false;
};

/// Waits for the child @p pid; true if it exited with status 0.
bool exited_successfully(const pid_t pid)
{
  int status = 0;
  pid_t done;
  do
    done = waitpid(pid, &status, 0);
  while (done == -1 && errno == EINTR);
  return done == pid && WIFEXITED(status) && WEXITSTATUS(status) == 0;
}
} // namespace

std::string find_program(const std::string& name)
{
  if (name.empty() || name.find('/') != std::string::npos)
    return is_executable_file(name) ? name : "";
  const char* path = std::getenv("PATH");
  const std::string directories = path != nullptr ? path : "/usr/bin:/bin";
  std::size_t begin = 0;
  while (begin <= directories.size())
  {
    const std::size_t end = std::min(directories.find(':', begin), directories.size());
    const std::string directory = directories.substr(begin, end - begin);
    if (!directory.empty() && is_executable_file(directory + "/" + name))
      return directory + "/" + name;
    begin = end + 1;
  }
  return "";
}

bool run_program(const std::string& program, const std::vector<std::string>& arguments,
                 const std::string& working_directory)
{
  SpawnActions spawn(working_directory);
  if (!spawn.ok)
    return false;
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(program.c_str()));
  for (const std::string& argument : arguments)
    argv.push_back(const_cast<char*>(argument.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, program.c_str(), &spawn.actions, nullptr, argv.data(), environ) !=
      0)
    return false;
  return exited_successfully(pid);
}
} // namespace pantocat
