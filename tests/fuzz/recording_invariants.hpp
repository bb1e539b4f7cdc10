// What every recording a reader returns must satisfy, whatever the input bytes: the promises of
// io/include/rockfit/io/recording.hpp. A violation aborts the fuzz run (a finding).
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "rockfit/io/recording.hpp"

namespace rockfit::fuzz {

[[noreturn]] inline void Violated(const char* what) {
  std::fprintf(stderr, "rockfit fuzz: recording invariant violated: %s\n", what);
  std::abort();
}

inline void CheckRecording(const io::Recording& r) {
  if (r.t_s.empty()) Violated("no samples");
  if (!(std::isfinite(r.rate_hz) && r.rate_hz > 0.0)) Violated("rate not finite and positive");
  if (r.w_B.size() != r.size()) Violated("w_B and t_s differ in length");
  if (r.has_euler() && r.euler_zyx.size() != r.size()) Violated("euler_zyx and t_s differ in length");
  if (r.has_accel() && r.accel_B.size() != r.size()) Violated("accel_B and t_s differ in length");
  if (r.t_s.front() != 0.0) Violated("first sample not at t = 0");
  for (std::size_t k = 0; k < r.size(); ++k) {
    if (!std::isfinite(r.t_s[k])) Violated("non-finite time");
    if (k > 0 && !(r.t_s[k] > r.t_s[k - 1])) Violated("times not strictly increasing");
    if (!r.w_B[k].allFinite()) Violated("non-finite angular velocity");
    if (r.has_euler() && !r.euler_zyx[k].allFinite()) Violated("non-finite Euler angle");
    if (r.has_accel() && !r.accel_B[k].allFinite()) Violated("non-finite specific force");
  }
  for (const auto& gap : r.gaps) {
    if (gap.index >= r.size()) Violated("gap index beyond the samples");
    if (!(std::isfinite(gap.duration_s) && gap.duration_s > 0.0)) Violated("gap duration not finite and positive");
  }
}

}  // namespace rockfit::fuzz
