// Generated Clough–Penzien ground motions acting along the block's x axis (io/stochastic_ground_motion.hpp), for
// tests and benchmarks that need records without files.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "rockfit/core/ground_motion.hpp"
#include "rockfit/io/stochastic_ground_motion.hpp"

namespace rockfit::testing {

// A record of `duration_s` (0.005 s steps, peak `pga_m_s2`, the generator's 0.3 g by default) along x; the envelope's rise and strong phase are
// shortened for short records (at most 20 % and 60 % of the duration) and the strong phase ends at
// `strong_end_s` at most.
inline core::GroundMotion GeneratedRecordAlongX(std::uint64_t seed, double duration_s,
                                                double pga_m_s2 = io::CloughPenzienOptions{}.pga_m_s2,
                                                double strong_end_s = 10.0) {
  io::CloughPenzienOptions o;
  o.seed = seed;
  o.duration_s = duration_s;
  o.pga_m_s2 = pga_m_s2;
  o.t_rise_s = std::min(o.t_rise_s, 0.2 * duration_s);
  o.t_strong_end_s = std::min(strong_end_s, 0.6 * duration_s);
  const std::vector<double> a = io::CloughPenzienRecord(o);
  std::vector<Eigen::Vector3d> a_W(a.size(), Eigen::Vector3d::Zero());
  for (std::size_t k = 0; k < a.size(); ++k) a_W[k].x() = a[k];
  return core::GroundMotion::Uniform(o.dt_s, a_W);
}

}  // namespace rockfit::testing
