#include "rockfit/io/atomic_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>
#include <utility>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "text/text_file.hpp"

namespace rockfit::io {

namespace {

std::atomic<unsigned> g_serial{0};

std::filesystem::path DirectoryOf(const std::filesystem::path& path) {
  return path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
}

// Flushes a file or a directory to disk; the errno of a failed fsync, else 0. A file or directory that cannot be
// opened for it counts as flushed (the rename stays atomic; only durability across a power cut is at stake).
int Fsync(const std::filesystem::path& path, int flags) {
  const int fd = ::open(path.c_str(), flags);
  if (fd < 0) return 0;
  const int error = ::fsync(fd) == 0 ? 0 : errno;
  ::close(fd);
  return error;
}

// The temporary's data must be on disk before it replaces the target: a write error that the file system reports
// only now (a full disk with delayed allocation, an I/O error) keeps the target as it was.
void FlushOrThrow(const std::filesystem::path& temporary, const std::filesystem::path& target) {
  if (const int error = Fsync(temporary, O_RDONLY); error != 0) {
    std::error_code ec;
    std::filesystem::remove(temporary, ec);
    throw OutputError(fmt::format("cannot write {}: {}; check free space", target.string(), std::strerror(error)));
  }
}

// The followed path (target) of a symbolic link or chain of links, else `path` itself. A link to a missing file
// gives the path it names, where the new file is then written.
std::filesystem::path FollowSymlinks(std::filesystem::path path) {
  constexpr int kMaxLinks = 40;  // as the kernel's own limit on a path's symbolic links (ELOOP)
  for (int links = 0; links < kMaxLinks; ++links) {
    std::error_code ec;
    if (!std::filesystem::is_symlink(std::filesystem::symlink_status(path, ec))) return path;
    const std::filesystem::path next = std::filesystem::read_symlink(path, ec);
    if (ec) throw OutputError(fmt::format("cannot follow the symbolic link {}: {}", path.string(), ec.message()));
    path = next.is_absolute() ? next : DirectoryOf(path) / next;
  }
  throw OutputError(fmt::format("{}: more than {} symbolic links in a chain (a loop?); give the path of a file",
                                path.string(), kMaxLinks));
}

}  // namespace

std::filesystem::path TemporaryPathFor(const std::filesystem::path& target, long pid, unsigned serial) {
  const std::filesystem::path dir = target.has_parent_path() ? target.parent_path() : std::filesystem::path();
  return dir / fmt::format(".{}{}{}-{}", target.filename().string(), kTemporaryMarker, pid, serial);
}

void RemoveStaleTemporaries(const std::filesystem::path& target) {
  const std::string prefix = "." + target.filename().string() + kTemporaryMarker;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(DirectoryOf(target), ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const std::string rest = name.substr(prefix.size());  // "<pid>-<serial>"
    const std::size_t dash = rest.find('-');
    if (dash == std::string::npos) continue;
    char* end = nullptr;
    const long pid = std::strtol(rest.substr(0, dash).c_str(), &end, 10);
    if (pid <= 0 || pid == static_cast<long>(::getpid())) continue;
    if (::kill(static_cast<pid_t>(pid), 0) == -1 && errno == ESRCH) std::filesystem::remove(entry.path(), ec);
  }
}

AtomicReplacement::AtomicReplacement(std::filesystem::path target) : target_(FollowSymlinks(std::move(target))) {
  if (target_.filename().empty()) throw OutputError(fmt::format("'{}' is not a file name", target_.string()));
  struct stat info {};
  if (::lstat(target_.c_str(), &info) == 0) {  // else a new file
    if (S_ISDIR(info.st_mode)) throw OutputError(fmt::format("{} is a directory; give a file name", target_.string()));
    if (!S_ISREG(info.st_mode)) {
      throw OutputError(fmt::format("{} is {}, not a regular file: rockfit writes a file by renaming a new one over "
                                    "the old, which would replace it; give the path of a regular file or a new one",
                                    target_.string(), DescribeFileType(info.st_mode)));
    }
  }
  RemoveStaleTemporaries(target_);
  temporary_ = TemporaryPathFor(target_, static_cast<long>(::getpid()), g_serial++);
}

AtomicReplacement::~AtomicReplacement() {
  if (pending_) Discard();
}

AtomicReplacement::AtomicReplacement(AtomicReplacement&& other) noexcept
    : target_(std::move(other.target_)), temporary_(std::move(other.temporary_)), pending_(other.pending_) {
  other.pending_ = false;
}

void AtomicReplacement::Discard() noexcept {
  std::error_code ec;
  std::filesystem::remove(temporary_, ec);
}

void AtomicReplacement::Write(const std::function<void(std::ostream&)>& write) {
  std::ofstream out(temporary_, std::ios::binary | std::ios::trunc);
  if (!out) {
    throw OutputError(fmt::format("cannot write {}: cannot create a file in {}: {}; check that the directory exists "
                                  "and is writable",
                                  target_.string(), DirectoryOf(target_).string(), std::strerror(errno)));
  }
  try {
    write(out);
  } catch (...) {
    out.close();
    Discard();
    throw;
  }
  out.close();
  if (!out) {
    const std::string reason = std::strerror(errno);
    Discard();
    throw OutputError(fmt::format("cannot write {}: {}; check free space", target_.string(), reason));
  }
  FlushOrThrow(temporary_, target_);
}

void AtomicReplacement::Commit() {
  FlushOrThrow(temporary_, target_);  // again for a temporary that a program wrote; nothing to do after Write()
  if (std::rename(temporary_.c_str(), target_.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    Discard();
    throw OutputError(fmt::format("cannot rename {} to {}: {}", temporary_.string(), target_.string(), reason));
  }
  pending_ = false;
  Fsync(DirectoryOf(target_), O_RDONLY | O_DIRECTORY);  // the rename itself; a failure here cannot be undone
}

void WriteFileAtomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write) {
  AtomicReplacement replacement(path);
  replacement.Write(write);
  replacement.Commit();
}

void WriteFilesAtomically(const std::vector<FileContent>& files) {
  std::vector<AtomicReplacement> replacements;
  replacements.reserve(files.size());
  for (const FileContent& file : files) {
    replacements.emplace_back(file.path);
    replacements.back().Write([&file](std::ostream& out) {
      out.write(file.text.data(), static_cast<std::streamsize>(file.text.size()));
    });
  }
  for (AtomicReplacement& replacement : replacements) replacement.Commit();
}

}  // namespace rockfit::io
