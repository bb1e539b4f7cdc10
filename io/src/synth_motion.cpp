#include "rockfit/io/synth_motion.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "rockfit/core/errors.hpp"

namespace rockfit::io {
namespace {
// A quaternion whose norm is off by more than this is not an attitude (round-off is ~1e-15).
constexpr double kUnitQuaternionTolerance = 1e-9;
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

}  // namespace rockfit::io
