// Reading one whole input file into memory, refusing before the first byte what is not an input file: a
// directory, a FIFO, a socket or a device (a FIFO would block for ever, /dev/zero would never end), a path with
// a NUL byte, and a file larger than the caller's limit (rockfit/io/input_limits.hpp).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace rockfit::io {

// The bytes of the regular file at `path` (a symbolic link is followed). Throws BadInput naming the path,
// what it is, `expected` (e.g. "a PEER AT2 file") and what to do.
std::string ReadRegularFile(const std::filesystem::path& path, const std::string& expected, std::uint64_t max_bytes);

// "a directory", "a FIFO (named pipe)", "a character device", … for the st_mode of something that is not a
// regular file.
std::string DescribeFileType(unsigned mode);

}  // namespace rockfit::io
