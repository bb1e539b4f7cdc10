// Progress of a long command on stderr with the time to go (`batch`, `fragility`): a bar redrawn in place on a
// terminal, one line per report otherwise (logs, CI).
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

namespace rockfit::app {

class ProgressBar {
 public:
  // `total` items, of which `already_done` were done by an earlier run (they do not enter the rate of the ETA).
  ProgressBar(std::string command, std::size_t total, std::size_t already_done, bool terminal);
  // `done` items finished in all; `what` is about the last of them.
  void Report(std::size_t done, const std::string& what);

 private:
  using Clock = std::chrono::steady_clock;
  std::string command_;
  std::size_t total_;
  std::size_t already_done_;
  bool terminal_;
  Clock::time_point start_;
};

// Whether stderr is a terminal (the bar is then redrawn in place).
bool StderrIsTerminal();

}  // namespace rockfit::app
