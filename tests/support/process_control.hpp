// Starting the real `rockfit` binary as a child process that the test can kill, wait for, or limit
// (setrlimit in the child before exec), for the crash-consistency and resource tests.
#pragma once

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "test_paths.hpp"

namespace rockfit::testing {

struct ChildLimits {
  std::optional<rlim_t> file_size_bytes;  // RLIMIT_FSIZE
};

// Starts `rockfit args...` in `working_dir` with stdout to /dev/null and stderr to `stderr_path` (or /dev/null).
inline pid_t StartRockfit(const std::vector<std::string>& args, const std::string& working_dir = {},
                          const std::string& stderr_path = {}, const ChildLimits& limits = {}) {
  const std::string binary = RockfitBinary().string();
  std::vector<std::string> copy = args;
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(binary.c_str()));
  for (std::string& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid != 0) return pid;
  if (!working_dir.empty() && ::chdir(working_dir.c_str()) != 0) ::_exit(126);
  if (limits.file_size_bytes) {
    const rlimit limit{*limits.file_size_bytes, *limits.file_size_bytes};
    if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) ::_exit(126);
  }
  if (!std::freopen("/dev/null", "r", stdin) || !std::freopen("/dev/null", "w", stdout) ||
      !std::freopen(stderr_path.empty() ? "/dev/null" : stderr_path.c_str(), "w", stderr)) {
    ::_exit(126);
  }
  ::execv(binary.c_str(), argv.data());
  ::_exit(127);
}

// Waits for the child; its exit code, or -signal when a signal ended it.
inline int WaitForExit(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return WIFSIGNALED(status) ? -WTERMSIG(status) : -1000;
}

// Runs to the end and returns {exit code, wall time in seconds}.
inline std::pair<int, double> RunRockfitTimed(const std::vector<std::string>& args,
                                              const std::string& working_dir = {}) {
  const auto start = std::chrono::steady_clock::now();
  const int code = WaitForExit(StartRockfit(args, working_dir));
  return {code, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
}

}  // namespace rockfit::testing
