// Output sampling of the simulator: samples at t_k = k / rate (or at given times), each taken from the
// integrator's dense output of the segment that contains it; a sample at an impact instant belongs to the
// segment after the impact (the post-impact value). Internal to the simulator.
#pragma once

#include <cstddef>
#include <limits>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "detail/euler_zyx_sequence.hpp"
#include "rockfit/core/attitude.hpp"
#include "rockfit/core/simulator.hpp"

namespace rockfit::core::detail {

class TrajectorySampler {
 public:
  // Samples up to and including t_last_s. Reserves the output vectors.
  TrajectorySampler(const SimulationOptions& options, double t_last_s, Trajectory* out);

  bool pending() const { return pending_; }
  double next_time() const { return next_time_; }
  bool with_attitude() const { return with_attitude_; }

  // Appends the sample at next_time() and moves on. `attitude()` returns q_WB, of unit norm to round-off (it is
  // not normalised again), and `euler(q_WB)` its Euler angles (φz, φy, φx) (a mode may know them without
  // conversion); they are only called when the options ask for attitudes.
  template <class AttitudeFn, class EulerFn>
  void Emit(const Mode& mode, const Eigen::Vector3d& w_B, const AttitudeFn& attitude, const EulerFn& euler) {
    out_->t_s.push_back(next_time_);
    out_->w_B.push_back(w_B);
    out_->mode.push_back(mode);
    if (with_attitude_) {
      const Eigen::Quaterniond q_WB = CanonicalUnitQuaternion(attitude());
      out_->q_WB.push_back(q_WB);
      out_->euler_zyx.push_back(euler(q_WB));
    }
    Advance();
  }
  // The sample of a run without attitudes (with_attitude() false): ω alone.
  void EmitRate(const Mode& mode, const Eigen::Vector3d& w_B) {
    out_->t_s.push_back(next_time_);
    out_->w_B.push_back(w_B);
    out_->mode.push_back(mode);
    Advance();
  }
  // The same with the Euler angles from the quaternion, by increments from the previous sample where it is the
  // one just before (EulerZyxSequence).
  template <class AttitudeFn>
  void Emit(const Mode& mode, const Eigen::Vector3d& w_B, const AttitudeFn& attitude) {
    Emit(mode, w_B, attitude, [this](const Eigen::Quaterniond& q_WB) { return euler_sequence_.Next(q_WB, index_); });
  }
  // Every pending sample before t_until_s (also at it when `inclusive`) in one state held constant (at rest, or
  // the end state of a run): the canonical attitude and its Euler angles are converted once, not per sample.
  void EmitHeld(const Mode& mode, const Eigen::Vector3d& w_B, const Eigen::Quaterniond& q_WB, double t_until_s,
                bool inclusive) {
    if (!(pending_ && (next_time_ < t_until_s || (inclusive && next_time_ == t_until_s)))) return;
    Eigen::Quaterniond q_canonical = q_WB;
    Eigen::Vector3d euler = Eigen::Vector3d::Zero();
    if (with_attitude_) {
      q_canonical = CanonicalQuaternion(q_WB);
      euler = EulerZyxFromQuaternion(q_canonical);
    }
    while (pending_ && (next_time_ < t_until_s || (inclusive && next_time_ == t_until_s))) {
      out_->t_s.push_back(next_time_);
      out_->w_B.push_back(w_B);
      out_->mode.push_back(mode);
      if (with_attitude_) {
        out_->q_WB.push_back(q_canonical);
        out_->euler_zyx.push_back(euler);
      }
      Advance();
    }
  }

 private:
  void Advance() {
    ++index_;
    if (times_ != nullptr) {
      pending_ = index_ < times_->size() && (*times_)[index_] <= t_last_s_;
      if (pending_) next_time_ = (*times_)[index_];
    } else {
      // t_k = k / rate, computed from k (no accumulated round-off).
      next_time_ = static_cast<double>(index_) / rate_hz_;
      pending_ = next_time_ <= t_last_s_;
    }
  }

  Trajectory* out_;
  const std::vector<double>* times_;  // explicit sample times, or null for k / rate
  double rate_hz_;
  double t_last_s_;
  bool with_attitude_;
  std::size_t index_ = 0;
  double next_time_ = 0.0;
  EulerZyxSequence euler_sequence_;
  bool pending_ = false;
};

}  // namespace rockfit::core::detail
