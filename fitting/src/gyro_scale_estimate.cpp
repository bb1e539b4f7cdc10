#include "rockfit/fitting/gyro_scale_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace rockfit::fitting {
namespace {

// The two-sided 95 % quantile of the normal distribution, as the other intervals use it.
constexpr double kZ95 = 1.959963984540054;

// The scale at `at`; false when the model fails there.
bool ScaleAt(const Objective& objective, const ParameterSet& at, Eigen::Vector3d* scale) {
  ErrorNodes nodes;
  ModelOutput output;
  const Evaluation e = objective.EvaluateDetailed(at, &nodes, &output);
  if (!e.feasible) return false;
  *scale = e.gyro_scale;
  return true;
}

// Newey–West long-run variance of Σ_k g_k with Bartlett weights up to max_lag.
double LongRunSumVariance(const std::vector<double>& g, int max_lag) {
  double v = 0.0;
  for (double x : g) v += x * x;
  const auto n = static_cast<int>(g.size());
  for (int lag = 1; lag <= std::min(max_lag, n - 1); ++lag) {
    double c = 0.0;
    for (int k = 0; k + lag < n; ++k) c += g[static_cast<std::size_t>(k)] * g[static_cast<std::size_t>(k + lag)];
    v += 2.0 * (1.0 - static_cast<double>(lag) / (max_lag + 1.0)) * c;
  }
  return std::max(v, 0.0);
}

}  // namespace

GyroScaleEstimate EstimateGyroScale(const Objective& objective, const ParameterSet& fitted, const UncertaintySummary& u,
                                    double widening_factor, const FitOptions& options) {
  GyroScaleEstimate out;
  out.mode = objective.options().gyro_scale;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (Interval& i : out.interval_95) i = {nan, nan};
  if (out.mode == GyroScaleMode::kOff) return out;
  ErrorNodes nodes;
  ModelOutput output;
  const Evaluation e = objective.EvaluateDetailed(fitted, &nodes, &output);
  if (!e.feasible || output.w_B.size() != nodes.size() || nodes.size() < 3) return out;
  out.available = true;
  out.value = e.gyro_scale;
  const Eigen::Vector3d s = e.gyro_scale;

  // Var(s | θ̂): the noise of the least-squares form, taken for that of the (28) minimiser (header comment).
  const double dt_s = nodes.duration_s() / static_cast<double>(nodes.size() - 1);
  const int max_lag = static_cast<int>(std::lround(options.intervals.noise_correlation_window_s / dt_s));
  const std::size_t n = nodes.size();
  std::array<std::vector<double>, 3> score;
  Eigen::Vector3d energy = Eigen::Vector3d::Zero();
  std::vector<double> score_common(n, 0.0);
  for (auto& g : score) g.assign(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector3d w_s = output.w_B[k].cwiseQuotient(s);  // the model's ω before scaling
    const Eigen::Vector3d residual = nodes.w_m_B[k] - output.w_B[k];
    for (int a = 0; a < 3; ++a) score[static_cast<std::size_t>(a)][k] = nodes.weight_s[k] * w_s[a] * residual[a];
    score_common[k] = nodes.weight_s[k] * w_s.dot(residual);
    energy += nodes.weight_s[k] * w_s.cwiseAbs2();
  }
  const double noise_factor = options.intervals.model_error_allowance * widening_factor * widening_factor;
  Eigen::Vector3d var_noise = Eigen::Vector3d::Constant(nan);
  if (out.mode == GyroScaleMode::kCommon) {
    var_noise.setConstant(noise_factor * LongRunSumVariance(score_common, max_lag) / (energy.sum() * energy.sum()));
  } else {
    for (int a = 0; a < 3; ++a) {
      if (energy[a] > kSilentAxisFraction * energy.sum()) {
        var_noise[a] = noise_factor * LongRunSumVariance(score[static_cast<std::size_t>(a)], max_lag) / (energy[a] * energy[a]);
      }
    }
  }

  // G·Cov(θ)·Gᵀ: the other parameters' uncertainty carried into the scale. Cov(θ) is the linearised one of the
  // 95 % level (σ_j and the correlation of the same M) times the widening factor², not one made of the final
  // interval ends: those are widened unequally (t0's floor, the hull with the profile, other basins), and with
  // t0 and α correlated by −0.99 or more a t0 σ from its floored interval no longer cancels along the ridge
  // t0 + T(α) — the scale's interval came out several times wider than its errors (fitting/README.md).
  std::vector<ParameterId> ids;
  std::vector<double> sigma;
  std::vector<Eigen::Vector3d> gradient;
  for (ParameterId id : objective.free_ids()) {
    const std::size_t j = static_cast<std::size_t>(id);
    const Interval& i95 = u.interval_95[j];
    if (!(std::isfinite(i95[0]) && std::isfinite(i95[1])) || !std::isfinite(u.linearised_sigma_95[j])) continue;
    const Parameter& p = fitted[id];
    const double h = options.ceres.difference_step[j];
    ParameterSet plus = fitted, minus = fitted;
    plus[id].value = std::min(p.upper, p.value + h);
    minus[id].value = std::max(p.lower, p.value - h);
    Eigen::Vector3d s_plus, s_minus;
    if (!(plus.value(id) > minus.value(id)) || !ScaleAt(objective, plus, &s_plus) || !ScaleAt(objective, minus, &s_minus)) {
      continue;
    }
    ids.push_back(id);
    sigma.push_back(widening_factor * u.linearised_sigma_95[j]);
    gradient.push_back((s_plus - s_minus) / (plus.value(id) - minus.value(id)));
  }
  Eigen::Vector3d var_parameters = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < ids.size(); ++i) {
    for (std::size_t j = 0; j < ids.size(); ++j) {
      double rho = i == j ? 1.0 : 0.0;
      const auto ri = static_cast<Eigen::Index>(ids[i]), rj = static_cast<Eigen::Index>(ids[j]);
      if (i != j && u.correlation.rows() > std::max(ri, rj) && std::isfinite(u.correlation(ri, rj))) {
        rho = u.correlation(ri, rj);
      }
      var_parameters += rho * sigma[i] * sigma[j] * gradient[i].cwiseProduct(gradient[j]);
    }
  }
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(var_noise[a])) continue;
    out.half_width_noise[a] = kZ95 * std::sqrt(var_noise[a]);
    out.half_width_parameters[a] = kZ95 * std::sqrt(std::max(0.0, var_parameters[a]));
    const double half = std::hypot(out.half_width_noise[a], out.half_width_parameters[a]);
    out.interval_95[static_cast<std::size_t>(a)] = {s[a] - half, s[a] + half};
    out.determined[static_cast<std::size_t>(a)] = 2.0 * half < kMaxGyroScaleError;
  }
  return out;
}

std::string GyroScaleJson(const GyroScaleEstimate& e) {
  if (e.mode == GyroScaleMode::kOff) return "null";
  auto number = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
  nlohmann::json intervals = nlohmann::json::array();
  for (const Interval& i : e.interval_95) {
    intervals.push_back(std::isfinite(i[0]) && std::isfinite(i[1]) ? nlohmann::json::array({i[0], i[1]}) : nlohmann::json());
  }
  return nlohmann::json{{"mode", ToString(e.mode)},
                        {"available", e.available},
                        {"value", {number(e.value[0]), number(e.value[1]), number(e.value[2])}},
                        {"interval_95", intervals},
                        {"determined", {e.determined[0], e.determined[1], e.determined[2]}},
                        {"half_width_noise", {number(e.half_width_noise[0]), number(e.half_width_noise[1]),
                                              number(e.half_width_noise[2])}},
                        {"half_width_parameters", {number(e.half_width_parameters[0]), number(e.half_width_parameters[1]),
                                                   number(e.half_width_parameters[2])}}}
      .dump();
}

std::string GyroScaleText(const GyroScaleEstimate& e) {
  if (e.mode == GyroScaleMode::kOff) return "not estimated";
  if (!e.available) return fmt::format("{}: not available (the model fails at the fit)", ToString(e.mode));
  std::string text = ToString(e.mode);
  static const char* const kAxes[] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    const Interval& i = e.interval_95[static_cast<std::size_t>(a)];
    text += fmt::format("{} s_{} = {:.5f}", a == 0 ? ":" : ",", kAxes[a], e.value[a]);
    text += std::isfinite(i[0]) ? fmt::format(" [{:.5f}, {:.5f}]", i[0], i[1]) : std::string(" (no motion about it)");
    if (std::isfinite(i[0]) && !e.determined[static_cast<std::size_t>(a)]) text += " not determined";
  }
  return text + " (95 %)";
}

}  // namespace rockfit::fitting
