#include "text/text_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <fmt/format.h>

#include "text/input_problem.hpp"

namespace rockfit::io {
namespace {

// Closes the descriptor however the read ends.
struct FileDescriptor {
  int fd = -1;
  ~FileDescriptor() {
    if (fd >= 0) ::close(fd);
  }
};

std::string Megabytes(std::uint64_t bytes) { return fmt::format("{:.0f} MB", static_cast<double>(bytes) / 1e6); }

}  // namespace

std::string DescribeFileType(unsigned mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  return "not a regular file";
}

std::string ReadRegularFile(const std::filesystem::path& path, const std::string& expected, std::uint64_t max_bytes) {
  const std::string name = path.string();
  if (name.find('\0') != std::string::npos) {
    std::string shown;
    for (char c : name) shown += c == '\0' ? std::string("\\0") : std::string(1, c);
    ThrowBadInput({{shown}, "path", "a NUL byte in the path", expected, "Remove the NUL byte from the path."});
  }
  struct stat info {};
  if (::stat(path.c_str(), &info) == 0 && !S_ISREG(info.st_mode)) {  // a socket cannot even be opened
    ThrowBadInput({{name}, "", DescribeFileType(info.st_mode), expected, "Give the path of a regular file."});
  }
  // O_NONBLOCK: opening a FIFO without a writer returns at once instead of waiting; the type is checked again on
  // what was opened, before anything is read.
  FileDescriptor file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
  if (file.fd < 0) {
    const int error = errno;
    ThrowBadInput({{name}, "", fmt::format("a file that cannot be opened ({})", std::strerror(error)), expected,
                   error == ENOENT ? "Check the path." : "Check the path and the file's permissions."});
  }
  if (::fstat(file.fd, &info) != 0 || !S_ISREG(info.st_mode)) {
    ThrowBadInput({{name}, "", DescribeFileType(info.st_mode), expected, "Give the path of a regular file."});
  }
  const auto size_bytes = static_cast<std::uint64_t>(info.st_size);
  if (size_bytes > max_bytes) {
    ThrowBadInput({{name}, "", fmt::format("a file of {} bytes ({})", size_bytes, Megabytes(size_bytes)), expected,
                   fmt::format("rockfit reads such files up to {} ({} bytes; docs/file-formats.md, \"Limits\"): "
                               "check that this is the right file, or split it.",
                               Megabytes(max_bytes), max_bytes)});
  }
  std::string text(static_cast<std::size_t>(size_bytes), '\0');
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t got = ::read(file.fd, text.data() + done, text.size() - done);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) {
      ThrowBadInput({{name}, "", fmt::format("a read error ({})", std::strerror(errno)), expected,
                     "Copy the file again and retry."});
    }
    if (got == 0) break;  // the file shrank while it was read: keep what is there
    done += static_cast<std::size_t>(got);
  }
  text.resize(done);
  return text;
}

}  // namespace rockfit::io
