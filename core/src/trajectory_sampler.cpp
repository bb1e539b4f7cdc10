#include "detail/trajectory_sampler.hpp"

#include <algorithm>
#include <cmath>

namespace rockfit::core::detail {
namespace {
// A run that may end before t_max (at phase 4, rest or overturning) reserves at most this many bytes of samples up
// front; the vectors grow past it as needed. Reserving t_max's worth (5,121 samples for 20 s at 256 Hz, ~0.5 MB
// with attitudes) for a run of one second made every run map, fault in and give back fresh pages: the C library
// returns freed memory at the top of the heap to the system above 128 KiB by default, so reservations below that
// are reused from one run to the next.
constexpr std::size_t kOpenEndedReserve_bytes = 64 * 1024;
}  // namespace

TrajectorySampler::TrajectorySampler(const SimulationOptions& options, double t_last_s, Trajectory* out)
    : out_(out),
      times_(options.sample_times_s.empty() ? nullptr : &options.sample_times_s),
      rate_hz_(options.rate_hz),
      t_last_s_(t_last_s),
      with_attitude_(options.sample_attitude) {
  std::size_t expected = 0;
  if (times_ != nullptr) {
    expected = times_->size();
  } else {
    expected = static_cast<std::size_t>(std::floor(t_last_s_ * rate_hz_)) + 1;
    if (options.stop != StopCondition::kTMax) {
      std::size_t sample_bytes = sizeof(double) + sizeof(Eigen::Vector3d) + sizeof(Mode);
      if (with_attitude_) sample_bytes += sizeof(Eigen::Quaterniond) + sizeof(Eigen::Vector3d);
      expected = std::min(expected, kOpenEndedReserve_bytes / sample_bytes);
    }
  }
  out_->t_s.reserve(expected);
  out_->w_B.reserve(expected);
  out_->mode.reserve(expected);
  if (with_attitude_) {
    out_->q_WB.reserve(expected);
    out_->euler_zyx.reserve(expected);
  }
  index_ = 0;
  if (times_ != nullptr) {
    pending_ = !times_->empty() && (*times_)[0] <= t_last_s_;
    next_time_ = pending_ ? (*times_)[0] : 0.0;
  } else {
    pending_ = true;
    next_time_ = 0.0;
  }
}

}  // namespace rockfit::core::detail
