#include <pantocat/base/input_error.h>
#include <pantocat/base/safe_files.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <dirent.h>
#include <fcntl.h>
#include <filesystem>
#include <random>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>
#include <utility>

namespace pantocat
{
namespace
{
/// "<what> <path>: <strerror(code)>" as a SimulationError.
SimulationError system_failure(const std::string& what, const std::string& path,
                               const int code)
{
  return SimulationError(what + " " + path + ": " + std::strerror(code));
}

/// @p n random letters and digits (std::random_device: the kernel's generator).
std::string random_characters(const unsigned int n)
{
  static const char alphabet[] = "abcdefghijklmnopqrstuvwxyz0123456789";
  std::random_device device;
  std::uniform_int_distribution<unsigned int> pick(0, sizeof alphabet - 2);
  std::string text;
  for (unsigned int i = 0; i < n; ++i)
    text += alphabet[pick(device)];
  return text;
}

/// write() of all @p size bytes of @p data; 0 or the errno of the failure.
int write_all(const int fd, const char* data, std::size_t size)
{
  while (size > 0)
  {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR)
      continue;
    if (n <= 0)
      return n < 0 ? errno : EIO;
    data += n, size -= static_cast<std::size_t>(n);
  }
  return 0;
}

/// unlinkat() of a non-directory entry; ENOENT counts as done. 0 or errno.
int unlink_entry(const int directory, const std::string& name)
{
  struct stat info;
  if (fstatat(directory, name.c_str(), &info, AT_SYMLINK_NOFOLLOW) != 0)
    return errno == ENOENT ? 0 : errno;
  if (S_ISDIR(info.st_mode))
    return EISDIR;
  if (unlinkat(directory, name.c_str(), 0) != 0 && errno != ENOENT)
    return errno;
  return 0;
}

/// What kind of file @p mode is, for a refusal.
std::string kind_of(const mode_t mode)
{
  if (S_ISFIFO(mode))
    return "a FIFO";
  if (S_ISCHR(mode))
    return "a character device";
  if (S_ISBLK(mode))
    return "a block device";
  if (S_ISDIR(mode))
    return "a directory";
  if (S_ISSOCK(mode))
    return "a socket";
  return "not a regular file";
}

/// @p path split into the directory to open it from and its last component.
std::pair<std::string, std::string> split_path(const std::string& path)
{
  const auto slash = path.rfind('/');
  if (slash == std::string::npos)
    return {".", path};
  return {slash == 0 ? "/" : path.substr(0, slash), path.substr(slash + 1)};
}

/// Creates @p name in @p directory afresh (see OutputFile); the descriptor.
int create_afresh(const int directory, const std::string& name, const std::string& path)
{
  for (unsigned int attempt = 0; attempt < 8; ++attempt)
  {
    if (const int code = unlink_entry(directory, name))
      throw system_failure(code == EISDIR ? "cannot write a file over the directory"
                                          : "cannot remove",
                           path, code);
    const int fd = openat(directory, name.c_str(),
                          O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd >= 0)
      return fd;
    if (errno != EEXIST) // EEXIST: planted again meanwhile; remove it again
      throw system_failure("cannot write", path, errno);
  }
  throw system_failure("cannot write", path, EEXIST);
}
} // namespace

bool is_safe_file_name(const std::string& name, const std::size_t max_length)
{
  if (name.empty() || name.size() > max_length || name[0] == '.' || name[0] == '-')
    return false;
  return std::all_of(name.begin(), name.end(),
                     [](const char c)
                     {
                       return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                              (c >= '0' && c <= '9') || c == '-' || c == '_' || c == '.';
                     });
}

void require_output_name(const std::string& parameter, const std::string& value)
{
  if (value.empty() || is_safe_file_name(value))
    return;
  const std::string shown = value.size() <= max_output_name_length + 16
                                ? value
                                : value.substr(0, max_output_name_length) + "... (" +
                                      std::to_string(value.size()) + " characters)";
  throw InputError(parameter + " = " + shown + ": a file base name of 1 to " +
                   std::to_string(max_output_name_length) +
                   " characters, each a letter, digit, '-', '_' or '.', not starting "
                   "with '.' or '-'");
}

const std::string& checked_file_name(const std::string& name)
{
  if (!is_safe_file_name(name, 255))
    throw SimulationError("internal error: unsafe file name " + name);
  return name;
}

void write_file_atomically(const std::string& file, const std::string& content)
{
  std::string temporary;
  int fd = -1;
  for (unsigned int attempt = 0; fd < 0 && attempt < 16; ++attempt)
  {
    temporary = file + ".tmp-" + random_characters(12);
    fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC,
                0666);
    if (fd < 0 && errno != EEXIST)
      throw system_failure("cannot write", file, errno);
  }
  if (fd < 0)
    throw system_failure("cannot write", file, EEXIST);
  int code = write_all(fd, content.data(), content.size());
  if (::close(fd) != 0 && code == 0)
    code = errno;
  if (code == 0 && std::rename(temporary.c_str(), file.c_str()) != 0)
    code = errno;
  if (code != 0)
  {
    ::unlink(temporary.c_str());
    throw system_failure("cannot write", file, code);
  }
}

void remove_output(const std::string& path)
{
  if (const int code = unlink_entry(AT_FDCWD, path))
    throw system_failure("cannot remove", path, code);
}

// ------------------------------------------------------------------ Directory

Directory Directory::open(const std::string& path)
{
  const int fd = ::open(path.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0)
    throw system_failure("cannot open the directory", path, errno);
  return Directory(fd, path);
}

Directory Directory::subdirectory(const Directory& parent, const std::string& name,
                                  bool* replaced_link)
{
  const std::string path = parent / name;
  if (replaced_link)
    *replaced_link = false;
  struct stat info;
  if (fstatat(parent.fd, name.c_str(), &info, AT_SYMLINK_NOFOLLOW) == 0 &&
      S_ISLNK(info.st_mode))
  {
    if (unlinkat(parent.fd, name.c_str(), 0) != 0)
      throw system_failure("cannot remove the link", path, errno);
    if (replaced_link)
      *replaced_link = true;
  }
  if (mkdirat(parent.fd, name.c_str(), 0777) != 0 && errno != EEXIST)
    throw system_failure("cannot create the directory", path, errno);
  const int fd =
      openat(parent.fd, name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0)
    throw system_failure("cannot open the directory", path,
                         errno == ELOOP ? ENOTDIR : errno);
  return Directory(fd, path);
}

std::optional<Directory> Directory::existing_subdirectory(const Directory& parent,
                                                          const std::string& name)
{
  const int fd =
      openat(parent.fd, name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0)
    return std::nullopt;
  return Directory(fd, parent / name);
}

Directory::Directory(Directory&& other) noexcept
    : fd(std::exchange(other.fd, -1)), name(std::move(other.name))
{
}

Directory& Directory::operator=(Directory&& other) noexcept
{
  if (this != &other)
  {
    if (fd >= 0)
      ::close(fd);
    fd = std::exchange(other.fd, -1);
    name = std::move(other.name);
  }
  return *this;
}

Directory::~Directory()
{
  if (fd >= 0)
    ::close(fd);
}

std::vector<std::string> Directory::files() const
{
  std::vector<std::string> names;
  const int copy = fcntl(fd, F_DUPFD_CLOEXEC, 0);
  DIR* stream = copy >= 0 ? fdopendir(copy) : nullptr;
  if (stream == nullptr)
  {
    if (copy >= 0)
      ::close(copy);
    throw system_failure("cannot read the directory", name, errno);
  }
  rewinddir(stream);
  while (const dirent* entry = readdir(stream))
  {
    const std::string file = entry->d_name;
    struct stat info;
    if (file != "." && file != ".." &&
        fstatat(fd, file.c_str(), &info, AT_SYMLINK_NOFOLLOW) == 0 &&
        !S_ISDIR(info.st_mode))
      names.push_back(file);
  }
  closedir(stream);
  std::sort(names.begin(), names.end());
  return names;
}

void Directory::remove_files(
    const std::function<bool(const std::string&)>& selected) const
{
  for (const std::string& file : files())
    if (selected(file))
      if (const int code = unlink_entry(fd, file))
        throw system_failure("cannot remove", *this / file, code);
}

bool Directory::contains(const std::string& entry) const
{
  struct stat info;
  return fstatat(fd, entry.c_str(), &info, AT_SYMLINK_NOFOLLOW) == 0;
}

// ----------------------------------------------------------------- FileBuffer

FileBuffer::FileBuffer(const int fd, std::string path, const std::uint64_t position)
    : fd(fd), file(std::move(path)), written(position), buffer(1 << 16)
{
  setp(buffer.data(), buffer.data() + buffer.size());
}

FileBuffer::~FileBuffer()
{
  if (fd >= 0)
  {
    drain();
    ::close(fd);
  }
}

bool FileBuffer::write_out(const char* data, const std::size_t size)
{
  if (error == 0 && fd >= 0)
    error = write_all(fd, data, size);
  if (error == 0)
    written += size;
  return error == 0;
}

bool FileBuffer::drain()
{
  const std::size_t size = pptr() - pbase();
  setp(buffer.data(), buffer.data() + buffer.size());
  return write_out(buffer.data(), size);
}

FileBuffer::int_type FileBuffer::overflow(const int_type c)
{
  if (!drain())
    return traits_type::eof();
  if (!traits_type::eq_int_type(c, traits_type::eof()))
    sputc(traits_type::to_char_type(c));
  return traits_type::not_eof(c);
}

std::streamsize FileBuffer::xsputn(const char* s, const std::streamsize n)
{
  if (n <= epptr() - pptr())
  {
    std::memcpy(pptr(), s, n);
    pbump(static_cast<int>(n));
    return n;
  }
  if (!drain() || !write_out(s, static_cast<std::size_t>(n)))
    return 0;
  return n;
}

int FileBuffer::sync()
{
  return drain() ? 0 : -1;
}

FileBuffer::pos_type FileBuffer::seekoff(const off_type offset,
                                         std::ios_base::seekdir way,
                                         std::ios_base::openmode which)
{
  // Only tellp(): the position of the next byte.
  if (offset != 0 || way != std::ios_base::cur || !(which & std::ios_base::out))
    return pos_type(off_type(-1));
  return pos_type(static_cast<off_type>(written + (pptr() - pbase())));
}

void FileBuffer::close()
{
  if (fd < 0)
  {
    if (error != 0)
      throw system_failure("cannot write", file, error);
    return;
  }
  drain();
  if (::close(fd) != 0 && error == 0)
    error = errno;
  fd = -1;
  if (error != 0)
    throw system_failure("cannot write", file, error);
}

// ----------------------------------------------------------------- OutputFile

OutputFile::OutputFile(const std::string& path) : std::ostream(nullptr)
{
  const auto [directory, name] = split_path(path);
  const Directory parent = Directory::open(directory);
  buffer = std::make_unique<FileBuffer>(create_afresh(parent.descriptor(), name, path),
                                        path, 0);
  rdbuf(buffer.get());
}

OutputFile::OutputFile(const Directory& directory, const std::string& name)
    : std::ostream(nullptr)
{
  const std::string path = directory / name;
  buffer = std::make_unique<FileBuffer>(create_afresh(directory.descriptor(), name, path),
                                        path, 0);
  rdbuf(buffer.get());
}

OutputFile::OutputFile(const std::string& path, const Append append)
    : std::ostream(nullptr)
{
  const int fd =
      ::open(path.c_str(), O_WRONLY | O_APPEND | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0)
  {
    // A link (ELOOP), a FIFO without a reader (ENXIO): say what it is.
    const int code = errno;
    struct stat info;
    if (lstat(path.c_str(), &info) == 0 && !S_ISREG(info.st_mode))
      throw SimulationError(
          "cannot append to " + path + ": it is " +
          (S_ISLNK(info.st_mode) ? "a symbolic link" : kind_of(info.st_mode)));
    throw system_failure("cannot append to", path, code);
  }
  struct stat info;
  int code = fstat(fd, &info) != 0 ? errno : 0;
  if (code == 0 && !S_ISREG(info.st_mode))
  {
    ::close(fd);
    throw SimulationError("cannot append to " + path + ": it is " +
                          kind_of(info.st_mode));
  }
  std::uint64_t size = code == 0 ? static_cast<std::uint64_t>(info.st_size) : 0;
  if (code == 0 && append.cut_to && *append.cut_to < size)
  {
    code = ftruncate(fd, static_cast<off_t>(*append.cut_to)) != 0 ? errno : 0;
    size = *append.cut_to;
  }
  if (code != 0)
  {
    ::close(fd);
    throw system_failure("cannot append to", path, code);
  }
  buffer = std::make_unique<FileBuffer>(fd, path, size);
  rdbuf(buffer.get());
}

OutputFile::~OutputFile() = default;

void OutputFile::check()
{
  if (buffer->pubsync() != 0 || !*this)
    buffer->close(); // throws with the reason
}

// ------------------------------------------------------------------ reading

FileContent read_regular_file(const std::string& path, const std::uint64_t max_bytes,
                              const bool follow_links)
{
  FileContent content;
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC |
                                          (follow_links ? 0 : O_NOFOLLOW));
  if (fd < 0)
  {
    content.missing = errno == ENOENT;
    content.problem =
        errno == ELOOP && !follow_links
            ? "is a symbolic link, not a regular file"
            : std::string("cannot be opened (") + std::strerror(errno) + ")";
    return content;
  }
  struct stat info;
  if (fstat(fd, &info) != 0)
    content.problem = std::string("cannot be read (") + std::strerror(errno) + ")";
  else if (!S_ISREG(info.st_mode))
    content.problem = "is " + kind_of(info.st_mode) + ", not a regular file";
  else if (static_cast<std::uint64_t>(info.st_size) > max_bytes)
    content.problem = "holds " + std::to_string(info.st_size) + " bytes, more than the " +
                      std::to_string(max_bytes) + " allowed";
  std::string bytes;
  for (char chunk[1 << 16]; content.problem.empty();)
  {
    const ssize_t n = ::read(fd, chunk, sizeof chunk);
    if (n < 0 && errno == EINTR)
      continue;
    if (n < 0)
      content.problem = std::string("cannot be read (") + std::strerror(errno) + ")";
    else if (n == 0)
      break;
    else if (bytes.size() + n > max_bytes)
      content.problem =
          "grows beyond the " + std::to_string(max_bytes) + " bytes allowed";
    else
      bytes.append(chunk, static_cast<std::size_t>(n));
  }
  ::close(fd);
  if (content.problem.empty())
    content.bytes = std::move(bytes);
  return content;
}

RegularFile regular_file(const std::string& path)
{
  RegularFile file;
  struct stat info;
  if (lstat(path.c_str(), &info) != 0)
  {
    file.missing = errno == ENOENT;
    file.problem = file.missing
                       ? "is missing"
                       : std::string("cannot be read (") + std::strerror(errno) + ")";
  }
  else if (S_ISLNK(info.st_mode))
    file.problem = "is a symbolic link, not a regular file";
  else if (!S_ISREG(info.st_mode))
    file.problem = "is " + kind_of(info.st_mode) + ", not a regular file";
  else
    file.size = static_cast<std::uint64_t>(info.st_size);
  return file;
}

// -------------------------------------------------------------- DirectoryLock

DirectoryLock::DirectoryLock(const std::string& directory)
    : file(directory + "/" + file_name())
{
  const int flags = O_RDWR | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC;
  for (unsigned int attempt = 0; fd < 0 && attempt < 4; ++attempt)
  {
    fd = ::open(file.c_str(), flags | O_CREAT | O_EXCL, 0666);
    made = fd >= 0;
    if (fd < 0 && errno == EEXIST)
      fd = ::open(file.c_str(), flags);
    if (fd < 0 && errno == ELOOP) // a link planted: replace it
      remove_output(file);
    else if (fd < 0 && errno != ENOENT) // ENOENT: removed meanwhile, again
      throw system_failure("cannot open the lock file", file, errno);
  }
  if (fd < 0)
    throw system_failure("cannot open the lock file", file, ELOOP);
  struct stat info;
  if (fstat(fd, &info) != 0 || !S_ISREG(info.st_mode))
    throw SimulationError("the lock file " + file + " is not a regular file");
  if (flock(fd, LOCK_EX | LOCK_NB) != 0)
  {
    if (errno != EWOULDBLOCK)
      throw system_failure("cannot lock", file, errno);
    return;
  }
  held = true;
  const std::string pid = std::to_string(getpid()) + "\n";
  if (ftruncate(fd, 0) != 0 || pwrite(fd, pid.data(), pid.size(), 0) < 0)
    throw system_failure("cannot write", file, errno);
}

DirectoryLock::~DirectoryLock()
{
  if (fd >= 0)
    ::close(fd); // releases the lock
}

std::string DirectoryLock::holder() const
{
  char text[32] = {};
  const ssize_t n = fd >= 0 ? pread(fd, text, sizeof text - 1, 0) : -1;
  std::string pid(text, n > 0 ? static_cast<std::size_t>(n) : 0);
  pid.erase(
      std::remove_if(pid.begin(), pid.end(), [](char c) { return c < '0' || c > '9'; }),
      pid.end());
  return pid;
}

void DirectoryLock::remove()
{
  if (fd < 0)
    return;
  if (held)
    ::unlink(file.c_str());
  ::close(fd);
  fd = -1;
  held = false;
}

// ----------------------------------------------------------- PrivateDirectory

PrivateDirectory::PrivateDirectory(const std::string& parent_directory)
    : parent(parent_directory)
{
  std::string pattern = parent + "/.private-XXXXXX";
  if (mkdtemp(pattern.data()) == nullptr)
    throw system_failure("cannot create a directory in", parent, errno);
  base = pattern.substr(parent.size() + 1);
}

PrivateDirectory::~PrivateDirectory()
{
  std::error_code ignored; // remove_all() follows no link
  std::filesystem::remove_all(parent + "/" + base, ignored);
}

bool PrivateDirectory::move_out(const std::string& entry, const std::string& target) const
{
  return std::rename((parent + "/" + base + "/" + entry).c_str(), target.c_str()) == 0;
}

std::uint64_t PrivateDirectory::size_of(const std::string& entry) const
{
  struct stat info;
  if (lstat((parent + "/" + base + "/" + entry).c_str(), &info) != 0 ||
      !S_ISREG(info.st_mode))
    return 0;
  return static_cast<std::uint64_t>(info.st_size);
}
} // namespace pantocat
