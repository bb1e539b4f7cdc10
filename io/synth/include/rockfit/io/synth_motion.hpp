// The true motion of a block at the sample times of a recording: the input of the measurement model
// (synth_measurement.hpp). It is made from a simulated trajectory (BlockMotionFromTrajectory below) or by hand.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "rockfit/core/block.hpp"
#include "rockfit/core/simulator.hpp"

namespace rockfit::io {

// One impact: the angular velocity jumps from w_minus_B to w_plus_B at recording time t_s.
struct ImpactJump {
  double t_s = 0.0;
  Eigen::Vector3d w_minus_B = Eigen::Vector3d::Zero();  // [rad/s]
  Eigen::Vector3d w_plus_B = Eigen::Vector3d::Zero();   // [rad/s]
};

struct BlockMotion {
  double rate_hz = 256.0;                  // samples at t_n = n / rate_hz, n = 0 … N−1 (recording time)
  std::vector<Eigen::Vector3d> w_B;        // angular velocity in the block frame [rad/s]
  std::vector<Eigen::Quaterniond> q_WB;    // attitude, block → world (unit quaternions)
  // A point of the block that is momentarily at rest (the contact vertex, or a point of the contact edge),
  // in B [m]. The sensor's acceleration is that of a rigid body turning about this point.
  std::vector<Eigen::Vector3d> p_BK_B;
  // Instants [s] where ω or dω/dt jumps (release, impacts, coming to rest, ascending). Angular
  // acceleration is estimated by differences of ω that never straddle one of them.
  std::vector<double> breaks_s;
  std::vector<ImpactJump> impacts;         // ascending in time
  double gravity_m_s2 = core::kStandardGravity;

  std::size_t size() const { return w_B.size(); }
  double t_s(std::size_t n) const { return static_cast<double>(n) / rate_hz; }
  // Throws InvalidArgument: sizes differ, empty, non-finite values, non-unit quaternions, unsorted times.
  void Validate() const;
};

// The true block motion of a simulated trial at every inertial sample: at rest at the trajectory's first
// sample before t0, the trajectory after it, at rest in its final attitude once it has ended. The pivot is the
// contact vertex or the midpoint of the contact edge. `trajectory` must be sampled at τ = 0 followed by
// τ_n = n / rate − t0 for n ≥ release_sample (as far as it reaches).
BlockMotion BlockMotionFromTrajectory(const core::Block& block, const core::Trajectory& trajectory, double t0_s,
                                      double rate_hz, std::size_t samples, std::size_t release_sample,
                                      double gravity_m_s2);

}  // namespace rockfit::io
