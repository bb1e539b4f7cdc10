#include "rockfit/io/atomic_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::io {

namespace {

std::atomic<unsigned> g_serial{0};

void Fsync(const std::filesystem::path& path, int flags) {
  const int fd = ::open(path.c_str(), flags);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

void RemoveStaleTemporaries(const std::filesystem::path& target) {
  const std::filesystem::path dir = target.has_parent_path() ? target.parent_path() : ".";
  const std::string prefix = "." + target.filename().string() + kTemporaryMarker;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
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

void WriteFileAtomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write) {
  if (path.filename().empty()) throw OutputError(fmt::format("'{}' is not a file name", path.string()));
  const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  const std::filesystem::path temporary =
      dir / fmt::format(".{}{}{}-{}", path.filename().string(), kTemporaryMarker, ::getpid(), g_serial++);
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw OutputError(fmt::format("{} is a directory; give a file name", path.string()));
  }
  RemoveStaleTemporaries(path);
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) {
      throw OutputError(fmt::format("cannot write {}: cannot create a file in {}: {}; check that the directory exists "
                                    "and is writable",
                                    path.string(), dir.string(), std::strerror(errno)));
    }
    try {
      write(out);
    } catch (...) {
      out.close();
      std::filesystem::remove(temporary, ec);
      throw;
    }
    out.flush();
    if (!out) {
      std::filesystem::remove(temporary, ec);
      throw OutputError(fmt::format("cannot write {}: {}; check free space", path.string(), std::strerror(errno)));
    }
  }
  Fsync(temporary, O_RDONLY);
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    std::filesystem::remove(temporary, ec);
    throw OutputError(fmt::format("cannot rename {} to {}: {}", temporary.string(), path.string(), reason));
  }
  Fsync(dir, O_RDONLY | O_DIRECTORY);
}

}  // namespace rockfit::io
