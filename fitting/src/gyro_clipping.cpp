#include "rockfit/fitting/gyro_clipping.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::fitting {

void GyroClippingOptions::Validate() const {
  if (!(std::isfinite(level_tolerance) && level_tolerance >= 0.0 && level_tolerance < 1.0)) {
    throw InvalidArgument(fmt::format("gyro clipping: level_tolerance must lie in [0, 1), got {}", level_tolerance));
  }
  if (min_samples < 2) {
    throw InvalidArgument(fmt::format("gyro clipping: min_samples must be at least 2 (one sample at the largest "
                                      "|ω| is every recording's peak), got {}",
                                      min_samples));
  }
}

GyroClipping DetectGyroClipping(const MeasuredSignal& signal, const GyroClippingOptions& options) {
  options.Validate();
  GyroClipping out;
  if (!options.enabled) return out;
  for (const Eigen::Vector3d& w : signal.w_B) out.level_rad_s = std::max(out.level_rad_s, w.cwiseAbs().maxCoeff());
  if (!(out.level_rad_s > 0.0) || !std::isfinite(out.level_rad_s)) return out;
  const double rail = (1.0 - options.level_tolerance) * out.level_rad_s;
  std::vector<bool> at_rail(signal.size(), false);
  std::vector<std::uint8_t> axes(signal.size(), 0);
  std::size_t count = 0;
  for (std::size_t k = 0; k < signal.size(); ++k) {
    for (int a = 0; a < 3; ++a) {
      if (std::abs(signal.w_B[k][a]) >= rail) axes[k] = static_cast<std::uint8_t>(axes[k] | (1u << a));
    }
    if (axes[k] != 0) {
      at_rail[k] = true;
      ++count;
    }
  }
  if (count < options.min_samples) return out;
  out.detected = true;
  out.samples = count;
  out.clipped = std::move(at_rail);
  out.axes = std::move(axes);
  return out;
}

}  // namespace rockfit::fitting
