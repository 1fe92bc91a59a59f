#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <ostream>
#include <streambuf>
#include <string>
#include <vector>

/**
 * @file
 * Every file the program writes or reads back from its output directory goes
 * through the functions of this header (doc/input-errors.md, "Files and
 * links"):
 * - a file is never written through a symbolic link: whole files are written
 *   to a temporary file of a random name, created exclusively, and renamed
 *   over the target (a link there is replaced, its target untouched);
 *   streamed files are created afresh after the entry at their name is
 *   removed, with O_CREAT | O_EXCL | O_NOFOLLOW;
 * - a directory inside the output directory (vtu/) is opened without
 *   following a link, so that nothing outside is cleared or written;
 * - a file read back (checkpoint, partial table, parameter file) must be a
 *   regular file of bounded size: a FIFO or a device is refused at once,
 *   without reading it;
 * - every failure names the file and the reason (errno at the failing call).
 * Failures are SimulationErrors; the callers turn refusals into InputErrors.
 */
namespace pantocat
{
/// The longest base name that Sweep/Output name and Study/Output name may give.
constexpr std::size_t max_output_name_length = 64;

/**
 * True if @p name is a plain file name of 1 to @p max_length characters,
 * each a letter, digit, '-', '_' or '.', not starting with '.' or '-': no
 * directory, no hidden file, nothing that a shell, gnuplot or a command line
 * would read as anything but a name.
 */
bool is_safe_file_name(const std::string& name,
                       std::size_t max_length = max_output_name_length);

/**
 * Throws an InputError "<parameter> = <value>: ..." unless @p value is empty
 * (the default name) or is_safe_file_name(). A long value is shown cut, with
 * its length.
 */
void require_output_name(const std::string& parameter, const std::string& value);

/**
 * @p name itself if it is a safe file name of at most 255 characters (the
 * names of generated files: plots, scripts, tables); a SimulationError
 * otherwise. Guards every file name written into a gnuplot script.
 */
const std::string& checked_file_name(const std::string& name);

/**
 * Writes @p content to @p file as a whole or not at all: into a temporary
 * file "<file>.tmp-<12 random characters>" of the same directory, created
 * with O_CREAT | O_EXCL | O_NOFOLLOW (a planted file or link of that name
 * makes it pick another name), written, closed, and renamed over @p file
 * (atomic on POSIX; a link at @p file is replaced, never followed). A reader,
 * or a run killed meanwhile, never sees the file half written. Throws a
 * SimulationError "cannot write <file>: <reason>" (a full disk is an error,
 * not a cut file); the temporary file is removed then.
 */
void write_file_atomically(const std::string& file, const std::string& content);

/**
 * Removes the entry @p path if it exists and is not a directory (a link is
 * removed itself, never its target). Throws a SimulationError "cannot remove
 * <path>: <reason>" if it exists and cannot be removed, or is a directory.
 */
void remove_output(const std::string& path);

/// A directory opened as a file descriptor (closed with the object).
class Directory
{
public:
  /**
   * The directory @p path, which may be reached through links (the output
   * directory is the user's choice). Throws a SimulationError.
   */
  static Directory open(const std::string& path);
  /**
   * The subdirectory @p name of @p parent, opened without following a link:
   * made if missing; a symbolic link there is removed and replaced by a new
   * directory (its target left as it is; @p replaced_link tells); any other
   * entry that is no directory is a SimulationError.
   */
  static Directory subdirectory(const Directory& parent, const std::string& name,
                                bool* replaced_link = nullptr);
  /**
   * The subdirectory @p name of @p parent if it is a directory (not a link),
   * else nothing.
   */
  static std::optional<Directory> existing_subdirectory(const Directory& parent,
                                                        const std::string& name);

  Directory(Directory&& other) noexcept;
  Directory& operator=(Directory&& other) noexcept;
  Directory(const Directory&) = delete;
  Directory& operator=(const Directory&) = delete;
  ~Directory();

  int descriptor() const { return fd; }
  const std::string& path() const { return name; }
  /// path() + "/" + @p entry.
  std::string operator/(const std::string& entry) const { return name + "/" + entry; }
  /// The names of the entries that are regular files or links (not "." or "..").
  std::vector<std::string> files() const;
  /**
   * Removes every entry that is not a directory and whose name @p selected
   * accepts. Throws a SimulationError naming the first that cannot be removed.
   */
  void remove_files(const std::function<bool(const std::string&)>& selected) const;
  /// True if the entry @p entry exists (links not followed).
  bool contains(const std::string& entry) const;

private:
  Directory(int fd, std::string path) : fd(fd), name(std::move(path)) {}
  int fd = -1;
  std::string name;
};

/// The buffer of an OutputFile: writes to a file descriptor, keeps errno.
class FileBuffer : public std::streambuf
{
public:
  FileBuffer(int fd, std::string path, std::uint64_t position);
  ~FileBuffer() override;
  FileBuffer(const FileBuffer&) = delete;
  FileBuffer& operator=(const FileBuffer&) = delete;
  /// Writes what is buffered and closes; throws a SimulationError on any failure.
  void close();
  const std::string& path() const { return file; }

protected:
  int_type overflow(int_type c) override;
  std::streamsize xsputn(const char* s, std::streamsize n) override;
  int sync() override;
  pos_type seekoff(off_type offset, std::ios_base::seekdir way,
                   std::ios_base::openmode which) override;

private:
  bool write_out(const char* data, std::size_t size);
  bool drain();

  int fd;
  std::string file;
  std::uint64_t written; ///< bytes handed to the file (its position)
  int error = 0;         ///< errno of the first failed call
  std::vector<char> buffer;
};

/**
 * A file written as a stream (time series, VTU frames, .pvd, gnuplot
 * scripts, tables). Created afresh: the entry at its name is removed first
 * if it is no directory (a link itself, never its target), then the file is
 * made with O_CREAT | O_EXCL | O_NOFOLLOW, so that no link planted meanwhile
 * is followed. Or, with Append, an existing regular file (no link, no FIFO)
 * opened for appending, first cut to a given length. Errors are kept with
 * their errno; close() (or check()) throws a SimulationError "cannot write
 * <file>: <reason>".
 */
class OutputFile : public std::ostream
{
public:
  struct Append
  {
    std::optional<std::uint64_t> cut_to; ///< the length to cut the file to first
  };

  /// Creates @p path afresh.
  explicit OutputFile(const std::string& path);
  /// Creates @p name afresh in @p directory (opened without following links).
  OutputFile(const Directory& directory, const std::string& name);
  /// Opens the regular file @p path for appending.
  OutputFile(const std::string& path, Append append);
  ~OutputFile() override;

  /// Flushes and closes; throws a SimulationError on any failure since opening.
  void close() { buffer->close(); }
  /// Flushes; throws a SimulationError on any failure since opening.
  void check();
  const std::string& path() const { return buffer->path(); }

private:
  std::unique_ptr<FileBuffer> buffer;
};

/// A regular file read whole, or why it was not.
struct FileContent
{
  std::optional<std::string> bytes; ///< the content, if read
  bool missing = false;             ///< there is no such file
  /// Else: "is a FIFO, not a regular file", "is a symbolic link", ...
  std::string problem;
};

/**
 * Reads the regular file @p path whole if it holds at most @p max_bytes
 * bytes. Opened with O_NONBLOCK (a FIFO does not block) and, unless
 * @p follow_links, O_NOFOLLOW; anything but a regular file (FIFO, device,
 * directory, socket, a link when not followed) is refused after fstat()
 * without reading a byte.
 */
FileContent read_regular_file(const std::string& path, std::uint64_t max_bytes,
                              bool follow_links);

/// The size of a regular file, or why there is none.
struct RegularFile
{
  std::optional<std::uint64_t> size; ///< if it is a regular file
  bool missing = false;              ///< there is no such file
  std::string problem;               ///< else: "is missing", "is a FIFO, ..."
};

/// lstat() of @p path: its size if it is a regular file (not a link).
RegularFile regular_file(const std::string& path);

/**
 * An exclusive lock on an output directory, held while the object lives: a
 * flock() on the file .pantocat-fem.lock inside it (made if missing; a link
 * there is replaced), which holds the process id of the run that has it.
 */
class DirectoryLock
{
public:
  /// The name of the lock file inside the directory.
  static const char* file_name() { return ".pantocat-fem.lock"; }
  /**
   * Tries to lock @p directory without waiting. Throws a SimulationError if
   * the lock file cannot be opened or locked for another reason than
   * another holder.
   */
  explicit DirectoryLock(const std::string& directory);
  DirectoryLock(const DirectoryLock&) = delete;
  DirectoryLock& operator=(const DirectoryLock&) = delete;
  ~DirectoryLock();
  /// False if another process holds the lock.
  bool locked() const { return held; }
  /// The process id in the lock file (its holder's, if locked() is false).
  std::string holder() const;
  /// True if this object made the lock file (there was none).
  bool made_file() const { return made; }
  /// Releases the lock and removes the lock file (that this object holds).
  void remove();

private:
  int fd = -1;
  bool held = false;
  bool made = false;
  std::string file;
};

/**
 * A directory made for this process only (mkdtemp: a random name, mode 0700)
 * inside @p parent, removed with all it holds when the object goes.
 */
class PrivateDirectory
{
public:
  explicit PrivateDirectory(const std::string& parent);
  PrivateDirectory(const PrivateDirectory&) = delete;
  PrivateDirectory& operator=(const PrivateDirectory&) = delete;
  ~PrivateDirectory();
  /// Its name inside the parent ("." + random characters).
  const std::string& name() const { return base; }
  /// Renames @p entry of this directory to @p target (a link there is replaced).
  bool move_out(const std::string& entry, const std::string& target) const;
  /// The size of @p entry of this directory, 0 if it is missing.
  std::uint64_t size_of(const std::string& entry) const;

private:
  std::string parent, base;
};
} // namespace pantocat
