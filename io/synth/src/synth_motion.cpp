#include "rockfit/io/synth_motion.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "rockfit/core/errors.hpp"

namespace rockfit::io {
namespace {
// A quaternion whose norm is off by more than this is not an attitude (round-off is ~1e-15).
constexpr double kUnitQuaternionTolerance = 1e-9;
// A trajectory sample time must match the requested one to this (the simulator samples exactly there).
constexpr double kSampleTimeTolerance_s = 1e-9;

Eigen::Vector3d PivotOf(const core::Block& block, const core::Mode& mode) {
  if (mode.kind == core::ModeKind::kVertex) return block.p_BV_B(mode.contact.first);
  if (mode.kind == core::ModeKind::kEdge) return 0.5 * (block.p_BV_B(mode.contact.first) + block.p_BV_B(mode.contact.second));
  return Eigen::Vector3d::Zero();  // at rest on the base: any point will do, nothing moves
}
}  // namespace

void BlockMotion::Validate() const {
  if (!(std::isfinite(rate_hz) && rate_hz > 0.0)) {
    throw InvalidArgument("BlockMotion: rate_hz must be a positive number, got " + std::to_string(rate_hz));
  }
  if (w_B.empty()) throw InvalidArgument("BlockMotion: no samples");
  if (q_WB.size() != w_B.size() || p_BK_B.size() != w_B.size()) {
    throw InvalidArgument("BlockMotion: w_B, q_WB and p_BK_B must have one entry per sample (" +
                          std::to_string(w_B.size()) + ", " + std::to_string(q_WB.size()) + ", " +
                          std::to_string(p_BK_B.size()) + ")");
  }
  for (std::size_t n = 0; n < w_B.size(); ++n) {
    if (!w_B[n].allFinite() || !p_BK_B[n].allFinite() || !q_WB[n].coeffs().allFinite()) {
      throw InvalidArgument("BlockMotion: non-finite value at sample " + std::to_string(n));
    }
    if (std::abs(q_WB[n].norm() - 1.0) > kUnitQuaternionTolerance) {
      throw InvalidArgument("BlockMotion: q_WB is not a unit quaternion at sample " + std::to_string(n));
    }
  }
  if (!std::is_sorted(breaks_s.begin(), breaks_s.end())) throw InvalidArgument("BlockMotion: breaks_s must be ascending");
  for (std::size_t i = 0; i < impacts.size(); ++i) {
    if (!std::isfinite(impacts[i].t_s) || !impacts[i].w_minus_B.allFinite() || !impacts[i].w_plus_B.allFinite()) {
      throw InvalidArgument("BlockMotion: non-finite impact " + std::to_string(i));
    }
    if (i > 0 && impacts[i].t_s < impacts[i - 1].t_s) throw InvalidArgument("BlockMotion: impacts must be ascending in time");
  }
  if (!(std::isfinite(gravity_m_s2) && gravity_m_s2 > 0.0)) throw InvalidArgument("BlockMotion: gravity must be positive");
}

BlockMotion BlockMotionFromTrajectory(const core::Block& block, const core::Trajectory& trajectory, double t0_s,
                                      double rate_hz, std::size_t samples, std::size_t release_sample, double gravity_m_s2) {
  if (trajectory.t_s.empty() || trajectory.q_WB.size() != trajectory.t_s.size() ||
      trajectory.w_B.size() != trajectory.t_s.size() || trajectory.mode.size() != trajectory.t_s.size()) {
    throw NumericalFailure("the simulated trajectory has no attitude samples; cannot synthesise a recording");
  }
  BlockMotion m;
  m.rate_hz = rate_hz;
  m.gravity_m_s2 = gravity_m_s2;
  m.w_B.reserve(samples);
  m.q_WB.reserve(samples);
  m.p_BK_B.reserve(samples);
  const double first_tau = static_cast<double>(release_sample) / rate_hz - t0_s;
  const std::size_t first_index = first_tau > 0.0 ? 1 : 0;  // trajectory index of the release sample
  const Eigen::Quaterniond q_release = trajectory.q_WB.front();
  const Eigen::Vector3d pivot_release = PivotOf(block, trajectory.mode.front());
  for (std::size_t n = 0; n < samples; ++n) {
    if (n < release_sample) {
      m.w_B.push_back(Eigen::Vector3d::Zero());
      m.q_WB.push_back(q_release);
      m.p_BK_B.push_back(pivot_release);
      continue;
    }
    const std::size_t k = first_index + (n - release_sample);
    if (k < trajectory.t_s.size()) {
      const double tau = static_cast<double>(n) / rate_hz - t0_s;
      if (std::abs(trajectory.t_s[k] - tau) > kSampleTimeTolerance_s) {
        throw NumericalFailure("the simulator returned a sample at τ = " + std::to_string(trajectory.t_s[k]) +
                               " s where τ = " + std::to_string(tau) + " s was requested");
      }
      m.w_B.push_back(trajectory.w_B[k]);
      m.q_WB.push_back(trajectory.q_WB[k].normalized());
      m.p_BK_B.push_back(PivotOf(block, trajectory.mode[k]));
    } else {
      // After the motion has ended: at rest in the final attitude.
      m.w_B.push_back(Eigen::Vector3d::Zero());
      m.q_WB.push_back(trajectory.q_WB.back().normalized());
      m.p_BK_B.push_back(Eigen::Vector3d::Zero());
    }
  }
  m.breaks_s.push_back(t0_s);
  for (const auto& impact : trajectory.impacts) {
    m.breaks_s.push_back(t0_s + impact.t_s);
    m.impacts.push_back({t0_s + impact.t_s, impact.w_minus_B, impact.w_plus_B});
  }
  m.breaks_s.push_back(t0_s + trajectory.t_end_s);
  std::sort(m.breaks_s.begin(), m.breaks_s.end());
  return m;
}

}  // namespace rockfit::io
