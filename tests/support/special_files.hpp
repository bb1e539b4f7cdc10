// Special files for tests of what rockfit refuses to read or replace: character devices made with mknod (the
// null and full devices' numbers, in the test's own directory, never under /dev), FIFOs and sockets.
#pragma once

#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>

namespace rockfit::testing {

// Linux's device numbers of /dev/null and /dev/full.
inline constexpr unsigned kNullDeviceMajor = 1, kNullDeviceMinor = 3;
inline constexpr unsigned kFullDeviceMajor = 1, kFullDeviceMinor = 7;

// False when the process may not make device nodes (not root): the caller skips the test.
inline bool MakeCharacterDevice(const std::filesystem::path& path, unsigned major, unsigned minor) {
  return ::mknod(path.c_str(), S_IFCHR | 0666, makedev(major, minor)) == 0;
}

inline bool MakeFifo(const std::filesystem::path& path) { return ::mkfifo(path.c_str(), 0600) == 0; }

// A listening-free Unix socket bound at `path`; the file stays after the descriptor is closed.
inline bool MakeSocketFile(const std::filesystem::path& path) {
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  if (path.native().size() >= sizeof(address.sun_path)) return false;
  std::strcpy(address.sun_path, path.c_str());
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  if (fd < 0) return false;
  const bool bound = ::bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) == 0;
  ::close(fd);
  return bound;
}

// The file type bits of `path` itself (a link is not followed).
inline mode_t FileTypeOf(const std::filesystem::path& path) {
  struct stat info {};
  if (::lstat(path.c_str(), &info) != 0) return 0;
  return info.st_mode & S_IFMT;
}

}  // namespace rockfit::testing
