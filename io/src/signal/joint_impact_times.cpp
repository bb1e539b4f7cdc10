#include "rockfit/io/joint_impact_times.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Dense>

#include "rockfit/core/errors.hpp"

namespace rockfit::io {

namespace {

// Standard deviations of the weak priors that only make the first error and the residual bias determined when an
// axis has a single reading: far beyond any levelled angle's error [rad] or residual gyro bias [rad/s].
constexpr double kLooseError_rad = 1.0;
constexpr double kLooseBias_rad_s = 1.0;

// Adds the squared residual (y − h·x)/σ to the normal equations: A += h·hᵀ/σ², b += h·y/σ².
struct NormalEquations {
  Eigen::MatrixXd a;
  Eigen::VectorXd b;
  explicit NormalEquations(Eigen::Index n) : a(Eigen::MatrixXd::Zero(n, n)), b(Eigen::VectorXd::Zero(n)) {}
  void Add(const std::vector<std::pair<Eigen::Index, double>>& h, double y, double sigma) {
    const double w = 1.0 / (sigma * sigma);
    for (const auto& [i, hi] : h) {
      b(i) += w * hi * y;
      for (const auto& [j, hj] : h) a(i, j) += w * hi * hj;
    }
  }
};

void RequireConsistent(const std::vector<SplitInterval>& splits, const std::vector<AxisReadings>& axes) {
  for (std::size_t j = 0; j < splits.size(); ++j) {
    const SplitInterval& s = splits[j];
    if (!std::isfinite(s.t0_s) || !std::isfinite(s.t1_s) || !(s.t1_s > s.t0_s) ||
        (j > 0 && s.t0_s < splits[j - 1].t1_s)) {
      throw InvalidArgument("EstimateJointImpactTimes: split " + std::to_string(j) +
                            " is not a sample interval after the one before it");
    }
  }
  for (std::size_t i = 0; i < axes.size(); ++i) {
    if (axes[i].rate_jump_rad_s.size() != splits.size()) {
      throw InvalidArgument("EstimateJointImpactTimes: axis " + std::to_string(i) +
                            " needs one rate jump per split");
    }
    for (std::size_t k = 0; k < axes[i].readings.size(); ++k) {
      const SplitReading& r = axes[i].readings[k];
      if (r.split >= splits.size() || (k > 0 && r.split <= axes[i].readings[k - 1].split) ||
          !std::isfinite(r.angle_rad) || !std::isfinite(r.rate_rad_s)) {
        throw InvalidArgument("EstimateJointImpactTimes: reading " + std::to_string(k) + " of axis " +
                              std::to_string(i) + " names no later split or is not finite");
      }
    }
  }
}

}  // namespace

void JointImpactOptions::Validate() const {
  if (!std::isfinite(reading_scatter_rad) || reading_scatter_rad <= 0.0) {
    throw InvalidArgument("joint impact times: reading_scatter_rad must be a positive number of radians");
  }
  if (!std::isfinite(drift_walk_rad_per_sqrt_s) || drift_walk_rad_per_sqrt_s <= 0.0) {
    throw InvalidArgument("joint impact times: drift_walk_rad_per_sqrt_s must be a positive number [rad/√s]");
  }
}

JointImpactSummary EstimateJointImpactTimes(const std::vector<SplitInterval>& splits,
                                            const std::vector<AxisReadings>& axes,
                                            const JointImpactOptions& options) {
  options.Validate();
  RequireConsistent(splits, axes);
  // Unknowns: δ_0 … δ_S−1, then for each axis its E_k (one per reading) and its β.
  const auto split_count = static_cast<Eigen::Index>(splits.size());
  std::vector<Eigen::Index> first_error(axes.size());
  Eigen::Index n = split_count;
  for (std::size_t i = 0; i < axes.size(); ++i) {
    first_error[i] = n;
    n += static_cast<Eigen::Index>(axes[i].readings.size()) + 1;
  }
  NormalEquations normal(n);
  for (Eigen::Index j = 0; j < split_count; ++j) {
    const double width_s = splits[static_cast<std::size_t>(j)].t1_s - splits[static_cast<std::size_t>(j)].t0_s;
    normal.Add({{j, 1.0}}, 0.0, width_s / std::sqrt(12.0));  // δ uniform within ±Δt/2
  }
  for (std::size_t i = 0; i < axes.size(); ++i) {
    const AxisReadings& axis = axes[i];
    const Eigen::Index e0 = first_error[i];
    const Eigen::Index beta = e0 + static_cast<Eigen::Index>(axis.readings.size());
    normal.Add({{beta, 1.0}}, 0.0, kLooseBias_rad_s);
    if (!axis.readings.empty()) normal.Add({{e0, 1.0}}, 0.0, kLooseError_rad);
    for (std::size_t k = 0; k < axis.readings.size(); ++k) {
      const SplitReading& r = axis.readings[k];
      // y_k = E_k + a_k·δ_k + Σ_{j<k} c_j·δ_j
      std::vector<std::pair<Eigen::Index, double>> h{{e0 + static_cast<Eigen::Index>(k), 1.0},
                                                     {static_cast<Eigen::Index>(r.split), r.rate_rad_s}};
      for (std::size_t j = 0; j < r.split; ++j) {
        if (axis.rate_jump_rad_s[j] != 0.0) h.emplace_back(static_cast<Eigen::Index>(j), axis.rate_jump_rad_s[j]);
      }
      normal.Add(h, r.angle_rad, options.reading_scatter_rad);
      if (k == 0) continue;
      // E_k − E_k−1 − β·(t_k − t_k−1): a random walk about the residual bias.
      const double gap_s = splits[r.split].middle_s() - splits[axis.readings[k - 1].split].middle_s();
      normal.Add({{e0 + static_cast<Eigen::Index>(k), 1.0}, {e0 + static_cast<Eigen::Index>(k) - 1, -1.0}, {beta, -gap_s}},
                 0.0, options.drift_walk_rad_per_sqrt_s * std::sqrt(gap_s));
    }
  }
  const Eigen::VectorXd x = normal.a.ldlt().solve(normal.b);
  JointImpactSummary summary;
  for (std::size_t j = 0; j < splits.size(); ++j) {
    const SplitInterval& s = splits[j];
    const double half_s = 0.5 * (s.t1_s - s.t0_s);
    const double offset_s = std::isfinite(x(static_cast<Eigen::Index>(j)))
                                ? std::clamp(x(static_cast<Eigen::Index>(j)), -half_s, half_s)
                                : 0.0;
    summary.offsets_s.push_back(offset_s);
    summary.times_s.push_back(s.middle_s() - offset_s);
  }
  for (std::size_t i = 0; i < axes.size(); ++i) {
    std::vector<double> errors;
    for (std::size_t k = 0; k < axes[i].readings.size(); ++k) errors.push_back(x(first_error[i] + static_cast<Eigen::Index>(k)));
    summary.errors_rad.push_back(errors);
  }
  return summary;
}

}  // namespace rockfit::io
