// Runs /usr/bin/python3 scripts that inspect HDF5 files with h5py (the reader MATLAB and Python users have).
// Tests skip when h5py is not installed.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "cli_runner.hpp"

namespace rockfit::testing {

inline const char* kPython = "/usr/bin/python3";

inline bool HaveH5py() {
  static const bool have = [] {
    const std::string command = std::string(kPython) + " -c 'import h5py, numpy' >/dev/null 2>&1";
    return std::system(command.c_str()) == 0;
  }();
  return have;
}

// Runs `script` with the file path as sys.argv[1]; returns the exit code and stdout+stderr.
inline CommandResult RunH5pyScript(const std::string& script, const std::filesystem::path& file) {
  static int counter = 0;
  const auto dir = std::filesystem::temp_directory_path() /
                   ("rockfit_h5py_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "check.py") << script;
  const std::string command = std::string(kPython) + " " + ShellQuote((dir / "check.py").string()) + " " +
                              ShellQuote(file.string()) + " >" + ShellQuote((dir / "out").string()) + " 2>&1";
  const int status = std::system(command.c_str());
  CommandResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = ReadWholeFile(dir / "out");
  std::filesystem::remove_all(dir);
  return result;
}

}  // namespace rockfit::testing

#define ROCKFIT_REQUIRE_H5PY()                                                                       \
  do {                                                                                               \
    if (!rockfit::testing::HaveH5py()) GTEST_SKIP() << "/usr/bin/python3 with h5py is not available"; \
  } while (0)
