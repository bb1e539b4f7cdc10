#include "rockfit/app/progress_bar.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <iostream>

#include <fmt/format.h>

namespace rockfit::app {

ProgressBar::ProgressBar(std::string command, std::size_t total, std::size_t already_done, bool terminal)
    : command_(std::move(command)), total_(total), already_done_(already_done), terminal_(terminal), start_(Clock::now()) {}

void ProgressBar::Report(std::size_t done, const std::string& what) {
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
  const std::size_t this_run = done > already_done_ ? done - already_done_ : 0;
  const double eta = this_run > 0 && total_ >= done
                         ? elapsed / static_cast<double>(this_run) * static_cast<double>(total_ - done)
                         : 0.0;
  if (terminal_) {
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(kWidth * done / std::max<std::size_t>(total_, 1));
    std::cerr << fmt::format("\r\033[K[{}{}] {}/{}  ETA {:.0f} s  {}", std::string(filled, '#'),
                             std::string(kWidth - filled, '.'), done, total_, eta, what.substr(0, 80))
              << (done == total_ ? "\n" : "") << std::flush;
  } else {
    std::cerr << fmt::format("rockfit {}: [{}/{}] {} (elapsed {:.1f} s, ETA {:.0f} s)\n", command_, done, total_, what,
                             elapsed, eta);
  }
}

bool StderrIsTerminal() { return isatty(fileno(stderr)) != 0; }

}  // namespace rockfit::app
