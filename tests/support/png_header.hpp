// The PNG signature and the IHDR chunk that must follow it: enough to tell a real picture of a given size from
// an empty or truncated file.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "cli_runner.hpp"

namespace rockfit::testing {

struct PngHeader {
  bool valid = false;
  std::uint32_t width = 0, height = 0;
};

inline PngHeader ReadPngHeader(const std::filesystem::path& path) {
  const std::string bytes = ReadWholeFile(path);
  PngHeader header;
  const std::string signature("\x89PNG\r\n\x1a\n", 8);
  if (bytes.size() < 33 || bytes.compare(0, 8, signature) != 0 || bytes.compare(12, 4, "IHDR") != 0) return header;
  const auto u32 = [&](std::size_t at) {  // big-endian
    return (std::uint32_t(std::uint8_t(bytes[at])) << 24) | (std::uint32_t(std::uint8_t(bytes[at + 1])) << 16) |
           (std::uint32_t(std::uint8_t(bytes[at + 2])) << 8) | std::uint32_t(std::uint8_t(bytes[at + 3]));
  };
  header.valid = true;
  header.width = u32(16);
  header.height = u32(20);
  return header;
}

}  // namespace rockfit::testing
