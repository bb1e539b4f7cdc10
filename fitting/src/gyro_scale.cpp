#include "rockfit/fitting/gyro_scale.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "rockfit/core/enum_names.hpp"
#include "rockfit/core/errors.hpp"

namespace rockfit::fitting {

const char* ToString(GyroScaleMode mode) {
  switch (mode) {
    case GyroScaleMode::kOff: return "off";
    case GyroScaleMode::kCommon: return "common";
    case GyroScaleMode::kPerAxis: return "per-axis";
  }
  return "?";
}

bool FromString(std::string_view text, GyroScaleMode* value) {
  static constexpr GyroScaleMode kAll[] = {GyroScaleMode::kOff, GyroScaleMode::kCommon, GyroScaleMode::kPerAxis};
  return core::FromStringAmong(text, kAll, value);
}

GyroScaleMode ParseGyroScaleMode(const std::string& name) {
  GyroScaleMode mode = GyroScaleMode::kOff;
  if (!FromString(name, &mode)) {
    throw InvalidArgument(
        fmt::format("unknown gyro scale estimate '{}': expected off, common (one scale for the three axes) or per-axis",
                    name));
  }
  return mode;
}

Eigen::Vector3d ProjectedGyroScale(const ErrorNodes& nodes, const std::vector<Eigen::Vector3d>& w_s_B,
                                   GyroScaleMode mode) {
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  if (mode == GyroScaleMode::kOff || w_s_B.size() != nodes.size()) return scale;
  Eigen::Vector3d cross = Eigen::Vector3d::Zero();   // Σ w ω_m,a ω_s,a
  Eigen::Vector3d energy = Eigen::Vector3d::Zero();  // Σ w ω_s,a²
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const unsigned censored = nodes.censored_axes.empty() ? 0u : nodes.censored_axes[k];
    for (int a = 0; a < 3; ++a) {
      if ((censored & (1u << a)) != 0) continue;  // a clipped reading is a bound on ω, not a measure of S·ω
      cross[a] += nodes.weight_s[k] * nodes.w_m_B[k][a] * w_s_B[k][a];
      energy[a] += nodes.weight_s[k] * w_s_B[k][a] * w_s_B[k][a];
    }
  }
  const double total = energy.sum();
  if (!(total > 0.0)) return scale;
  auto clamp = [](double s) { return std::clamp(s, 1.0 - kMaxGyroScaleError, 1.0 + kMaxGyroScaleError); };
  if (mode == GyroScaleMode::kCommon) return Eigen::Vector3d::Constant(clamp(cross.sum() / total));
  for (int a = 0; a < 3; ++a) {
    if (energy[a] > kSilentAxisFraction * total) scale[a] = clamp(cross[a] / energy[a]);
  }
  return scale;
}

}  // namespace rockfit::fitting
