#include "rockfit/fitting/residual_jacobian.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

#include <fmt/format.h>

namespace rockfit::fitting {
namespace {

// The column of core::SampleSensitivity for a model parameter; −1 for one without (τ_edge, the release roll) and
// for t0.
int SensitivityColumnOf(ParameterId id) {
  switch (id) {
    case ParameterId::kAlpha: return static_cast<int>(core::SensitivityColumn::kAlpha);
    case ParameterId::kLambda: return static_cast<int>(core::SensitivityColumn::kLambda);
    case ParameterId::kLambdaLat: return static_cast<int>(core::SensitivityColumn::kLambdaLat);
    case ParameterId::kLambdaLon: return static_cast<int>(core::SensitivityColumn::kLambdaLon);
    case ParameterId::kT0:
    case ParameterId::kTauEdge:
    case ParameterId::kReleaseRoll: break;
  }
  return -1;
}

// The slope of the linear interpolation of the measured signal at t (MeasuredSignal::Interpolate), from the
// sample after t; 0 where the interpolation is clamped.
Eigen::Vector3d InterpolationSlope(const MeasuredSignal& signal, double t) {
  if (t < signal.t_s.front() || t >= signal.t_s.back()) return Eigen::Vector3d::Zero();
  const auto upper = std::upper_bound(signal.t_s.begin(), signal.t_s.end(), t);
  const std::size_t k = static_cast<std::size_t>(std::distance(signal.t_s.begin(), upper));
  return (signal.w_B[k] - signal.w_B[k - 1]) / (signal.t_s[k] - signal.t_s[k - 1]);
}

}  // namespace

double ResidualScale::Scale(double weight_s, double window_s) const {
  return kind == Kind::kSoftL1 ? (t_ref_s / window_s) * weight_s / std::sqrt(nominal_dt_s) : std::sqrt(weight_s);
}

double ResidualScale::ScaleDerivativeT0(double weight_s, double dweight_dt0, double window_s) const {
  if (kind == Kind::kSoftL1) {
    // s = c·w/T with T = t_end − t0: ∂s/∂t0 = c (∂w/∂t0 / T + w / T²).
    const double c = t_ref_s / std::sqrt(nominal_dt_s);
    return c * (dweight_dt0 / window_s + weight_s / (window_s * window_s));
  }
  return weight_s > 0.0 ? 0.5 * dweight_dt0 / std::sqrt(weight_s) : 0.0;
}

ResidualJacobianSummary NodeResiduals(const Objective& objective, const ErrorNodes& nodes, const ModelOutput& output,
                                      const ResidualScale& scale, std::vector<NodeResidual>* residuals) {
  ResidualJacobianSummary summary;
  const std::size_t n = nodes.size();
  const auto num_free = static_cast<Eigen::Index>(objective.num_free());
  residuals->resize(n);
  // The window's length without its clipped samples, as the soft-L1 scaling of (28) uses it.
  const double window_s = nodes.weighted_duration_s();
  for (std::size_t i = 0; i < n; ++i) {
    (*residuals)[i].f = scale.Scale(nodes.weight_s[i], window_s) * NodeMisfit(nodes, i, output.w_B[i]);
    (*residuals)[i].df_dx.setZero(3, num_free);
  }
  if (output.dw_B_dparams.size() != n) {
    summary.reason = "the model gave no exact derivatives for this run";
    return summary;
  }
  // With clipped samples the window's length depends on t0 through them too; the t0 column below does not say so.
  if (nodes.num_excluded > 0 || nodes.num_censored > 0) {
    summary.reason = "clipped samples in the window";
    return summary;
  }
  const Eigen::Vector3d dw_m0_dt0 = InterpolationSlope(objective.signal(), nodes.t_s.front());
  constexpr int kTime = static_cast<int>(core::SensitivityColumn::kTime);
  for (Eigen::Index j = 0; j < num_free; ++j) {
    const ParameterId id = objective.free_ids()[static_cast<std::size_t>(j)];
    if (id == ParameterId::kT0) {
      for (std::size_t i = 0; i < n; ++i) {
        // Only the first two weights depend on t0: w_0 = (t_1 − t0)/2 and w_1 = (t_2 − t0)/2 (or (t_1 − t0)/2).
        const double dweight = i <= 1 ? -0.5 : 0.0;
        const double s = scale.Scale(nodes.weight_s[i], window_s);
        Eigen::Vector3d d = scale.ScaleDerivativeT0(nodes.weight_s[i], dweight, window_s) *
                            (nodes.w_m_B[i] - output.w_B[i]);
        if (i == 0) d += s * dw_m0_dt0;
        if (i >= 1) d += s * output.dw_B_dparams[i].col(kTime);
        (*residuals)[i].df_dx.col(j) = d;
      }
      continue;
    }
    const int column = SensitivityColumnOf(id);
    if (column < 0) {
      summary.reason = fmt::format("no exact derivative with respect to {}", Name(id));
      return summary;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector3d dw = output.dw_B_dparams[i].col(column);
      if (!dw.allFinite()) {
        summary.reason = fmt::format("the derivative with respect to {} does not exist here", Name(id));
        return summary;
      }
      (*residuals)[i].df_dx.col(j) = -scale.Scale(nodes.weight_s[i], window_s) * dw;
    }
  }
  summary.available = true;
  return summary;
}

}  // namespace rockfit::fitting
