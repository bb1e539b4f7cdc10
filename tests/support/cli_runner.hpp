// Runs the real `rockfit` binary with arguments and captures exit code, stdout and stderr.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "test_paths.hpp"

namespace rockfit::testing {

struct CommandResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string ShellQuote(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'') q += "'\\''";
    else q += c;
  }
  return q + "'";
}

inline std::string ReadWholeFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Runs `rockfit args...` in `working_dir` (the current directory when empty), with its virtual memory limited to
// `virtual_memory_kib` (ulimit -v) when that is not 0.
inline CommandResult RunRockfit(const std::vector<std::string>& args, const std::filesystem::path& working_dir = {},
                                unsigned long virtual_memory_kib = 0) {
  static int counter = 0;
  const auto tmp = std::filesystem::temp_directory_path() /
                   ("rockfit_cli_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
  std::filesystem::create_directories(tmp);
  std::string command;
  if (virtual_memory_kib > 0) command += "ulimit -v " + std::to_string(virtual_memory_kib) + " && ";
  if (!working_dir.empty()) command += "cd " + ShellQuote(working_dir.string()) + " && ";
  command += ShellQuote(RockfitBinary().string());
  for (const auto& a : args) command += " " + ShellQuote(a);
  command += " </dev/null >" + ShellQuote((tmp / "out").string()) + " 2>" + ShellQuote((tmp / "err").string());
  const int status = std::system(command.c_str());
  CommandResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = ReadWholeFile(tmp / "out");
  result.err = ReadWholeFile(tmp / "err");
  std::filesystem::remove_all(tmp);
  return result;
}

}  // namespace rockfit::testing
