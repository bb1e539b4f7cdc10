// Shared helpers of the libFuzzer targets (tests/fuzz/README.md).
//
// Readers that take a path get the fuzz input as files in a private scratch directory under /dev/shm
// (RAM, so a run costs no disk I/O); readers that parse text get it from memory. One input may hold
// several files: the bytes up to the first "\n@@@ NAME\n" line are the main file, each such line
// starts the file NAME (one of the names the target allows; others are skipped).
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rockfit/core/errors.hpp"

namespace rockfit::fuzz {

// The line that starts a further file of a multi-file input.
inline constexpr std::string_view kFileMarker = "\n@@@ ";

struct FilePart {
  std::string name;  // empty for the main file
  std::string_view bytes;
};

// Splits `data` at "\n@@@ NAME\n" lines. The main file comes first, with an empty name.
inline std::vector<FilePart> SplitFiles(std::string_view data) {
  std::vector<FilePart> parts;
  std::string name;
  for (;;) {
    const std::size_t marker = data.find(kFileMarker);
    parts.push_back({name, data.substr(0, marker)});
    if (marker == std::string_view::npos) break;
    const std::size_t name_start = marker + kFileMarker.size();
    const std::size_t name_end = data.find('\n', name_start);
    if (name_end == std::string_view::npos) break;
    name = std::string(data.substr(name_start, name_end - name_start));
    data.remove_prefix(name_end + 1);
  }
  return parts;
}

// A directory of its own under /dev/shm (else the system's temporary directory), emptied per input.
class ScratchDir {
 public:
  ScratchDir() {
    const std::filesystem::path shm = "/dev/shm";
    const std::filesystem::path base =
        std::filesystem::is_directory(shm) ? shm : std::filesystem::temp_directory_path();
    path_ = base / ("rockfit_fuzz_" + std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  const std::filesystem::path& path() const { return path_; }

  // Removes what the previous input left.
  void Clear() const {
    for (const auto& entry : std::filesystem::directory_iterator(path_)) std::filesystem::remove_all(entry.path());
  }

  std::filesystem::path Write(const std::string& name, std::string_view bytes) const {
    const std::filesystem::path file = path_ / name;
    std::ofstream out(file, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return file;
  }

 private:
  std::filesystem::path path_;
};

// Runs `read` and accepts the errors the readers document (the CLI turns them into exit codes 1, 2
// and 3). Anything else — another exception type, a crash, a sanitizer report — is a finding:
// libFuzzer stops on the uncaught exception.
template <typename Read>
void ExpectDocumentedOutcome(Read&& read) {
  try {
    std::forward<Read>(read)();
  } catch (const rockfit::BadInput&) {
  } catch (const rockfit::InvalidArgument&) {
  } catch (const rockfit::NumericalFailure&) {
  }
}

inline std::string_view AsText(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

}  // namespace rockfit::fuzz
