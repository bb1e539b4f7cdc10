#include "rockfit/fitting/gyro_scale.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <fmt/format.h>

#include "rockfit/core/enum_names.hpp"
#include "rockfit/core/errors.hpp"

namespace rockfit::fitting {

namespace {

double ClampScale(double s) { return std::clamp(s, 1.0 - kMaxGyroScaleError, 1.0 + kMaxGyroScaleError); }

// Σ_k w_k ω_s,a² per axis: how much the model moves about each axis.
Eigen::Vector3d ModelEnergy(const ErrorNodes& nodes, const std::vector<Eigen::Vector3d>& w_s_B) {
  Eigen::Vector3d energy = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < nodes.size(); ++k) energy += nodes.weight_s[k] * w_s_B[k].cwiseAbs2();
  return energy;
}

struct Slope {
  double first = 0.0;   // dF/ds [rad]
  double second = 0.0;  // d²F/ds² [rad]
};

// The slope and curvature of F(S) = Σ_k w_k ‖d_k(S)‖ (gyro_scale.hpp) along s, where S = base with the axes in
// `along` (entries 1) set to s. The misfit is NodeMisfit's, so a censored component counts while the model falls
// short of the rail (d ≠ 0) and not beyond it.
Slope SlopeAlong(const ErrorNodes& nodes, const std::vector<Eigen::Vector3d>& w_s_B, const Eigen::Vector3d& along,
                 double s, const Eigen::Vector3d& base) {
  const Eigen::Vector3d scale = base.cwiseProduct(Eigen::Vector3d::Ones() - along) + s * along;
  Slope out;
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    if (nodes.weight_s[k] == 0.0) continue;
    const Eigen::Vector3d w_s = w_s_B[k].cwiseProduct(along);  // d(S·ω_s)/ds
    const Eigen::Vector3d d = NodeMisfit(nodes, k, scale.cwiseProduct(w_s_B[k]));
    const double norm = d.norm();
    if (!(norm > 0.0)) continue;  // a node fitted exactly: the subgradient 0
    const std::uint8_t censored = nodes.censored_axes.empty() ? 0 : nodes.censored_axes[k];
    double active = 0.0;  // Σ_{a active} ω_s,a²
    for (int a = 0; a < 3; ++a) {
      if ((censored & (1u << a)) == 0 || d[a] != 0.0) active += w_s[a] * w_s[a];
    }
    const double projection = d.dot(w_s);
    out.first -= nodes.weight_s[k] * projection / norm;
    out.second += nodes.weight_s[k] * (active / norm - projection * projection / (norm * norm * norm));
  }
  return out;
}

// The minimiser of F along s on [1 − kMaxGyroScaleError, 1 + kMaxGyroScaleError] (gyro_scale.hpp): safeguarded
// Newton on the slope from `start`, a bracket [lo, hi] of the sign change, stop when it is narrower than
// kGyroScaleTolerance.
double MinimiseAlong(const ErrorNodes& nodes, const std::vector<Eigen::Vector3d>& w_s_B, const Eigen::Vector3d& along,
                     double start, const Eigen::Vector3d& base) {
  double lo = 1.0 - kMaxGyroScaleError, hi = 1.0 + kMaxGyroScaleError;
  bool rising_seen = false, falling_seen = false;  // a slope > 0 (hi moved) / < 0 (lo moved) evaluated
  double s = ClampScale(start);
  double last_step = hi - lo;  // the previous iteration's step
  for (int iteration = 0; iteration < kMaxGyroScaleIterations && hi - lo > kGyroScaleTolerance; ++iteration) {
    const Slope slope = SlopeAlong(nodes, w_s_B, along, s, base);
    if (slope.first == 0.0 || !std::isfinite(slope.first)) return s;  // the minimiser (or nothing to go on)
    if (slope.first < 0.0) {
      lo = s;
      falling_seen = true;
    } else {
      hi = s;
      rising_seen = true;
    }
    double next = slope.second > 0.0 ? s - slope.first / slope.second : std::numeric_limits<double>::quiet_NaN();
    // A Newton step shorter than half the tolerance is lengthened to it, so that the bracket closes.
    if (std::abs(next - s) < 0.5 * kGyroScaleTolerance) next = s + std::copysign(0.5 * kGyroScaleTolerance, -slope.first);
    // Bisection when Newton leaves the bracket or does not at least halve its step (a kink of F, where a node
    // is fitted exactly, can make it crawl).
    if (!(next > lo && next < hi) || std::abs(next - s) > 0.5 * last_step) next = 0.5 * (lo + hi);
    last_step = std::abs(next - s);
    s = next;
  }
  if (hi - lo > kGyroScaleTolerance) return s;  // the cap (never reached): the last iterate
  // F falls (rises) all the way to a bound: the bound itself is the minimiser.
  if (!rising_seen) return 1.0 + kMaxGyroScaleError;
  if (!falling_seen) return 1.0 - kMaxGyroScaleError;
  return 0.5 * (lo + hi);
}

}  // namespace

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

Eigen::Vector3d LeastSquaresGyroScale(const ErrorNodes& nodes, const std::vector<Eigen::Vector3d>& w_s_B,
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
  if (mode == GyroScaleMode::kCommon) return Eigen::Vector3d::Constant(ClampScale(cross.sum() / total));
  for (int a = 0; a < 3; ++a) {
    if (energy[a] > kSilentAxisFraction * total) scale[a] = ClampScale(cross[a] / energy[a]);
  }
  return scale;
}

Eigen::Vector3d ProjectedGyroScale(const ErrorNodes& nodes, const std::vector<Eigen::Vector3d>& w_s_B,
                                   GyroScaleMode mode) {
  Eigen::Vector3d scale = LeastSquaresGyroScale(nodes, w_s_B, mode);
  if (mode == GyroScaleMode::kOff || w_s_B.size() != nodes.size()) return scale;
  if (mode == GyroScaleMode::kCommon) {
    const double s = MinimiseAlong(nodes, w_s_B, Eigen::Vector3d::Ones(), scale[0], scale);
    return Eigen::Vector3d::Constant(s);
  }
  const Eigen::Vector3d energy = ModelEnergy(nodes, w_s_B);
  const double total = energy.sum();
  if (!(total > 0.0)) return scale;
  for (int sweep = 0; sweep < kMaxPerAxisSweeps; ++sweep) {
    double largest_move = 0.0;
    for (int a = 0; a < 3; ++a) {
      if (!(energy[a] > kSilentAxisFraction * total)) continue;  // a silent axis keeps 1
      const double s = MinimiseAlong(nodes, w_s_B, Eigen::Vector3d::Unit(a), scale[a], scale);
      largest_move = std::max(largest_move, std::abs(s - scale[a]));
      scale[a] = s;
    }
    if (largest_move <= kPerAxisSweepTolerance) break;
  }
  return scale;
}

}  // namespace rockfit::fitting
