// A trajectory model that gives "exact" sensitivities for a model without them (the analytic test model), by
// central differences of its closed form: for tests of the machinery that uses ModelOutput::dw_B_dparams (the
// exact profile re-fits), where the simulator's own derivatives would make the test slow. Between impacts the
// analytic model is smooth in every parameter and in time, so the differences agree with the derivatives to
// O(h²) there; a sample within h of an impact gets the slope across the jump, as a sample on an impact would.
#pragma once

#include <algorithm>
#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "rockfit/core/planar_sensitivity.hpp"
#include "rockfit/fitting/trajectory_model.hpp"

namespace rockfit::testing {

class DifferencedSensitivityModel final : public fitting::TrajectoryModel {
 public:
  // Difference step of every parameter and of time: small against the scales the fits resolve (0.1 ms, 0.1 mrad,
  // 1e-3 of the λ's), large enough that round-off of ω (1e-16 rad/s relative) stays below 1e-8 of the slope.
  static constexpr double kStep = 1e-6;

  explicit DifferencedSensitivityModel(std::shared_ptr<const fitting::TrajectoryModel> model) : model_(std::move(model)) {}

  void Evaluate(const core::ModelParameters& params, const std::vector<double>& times,
                fitting::ModelOutput* out) const override {
    model_->Evaluate(params, times, out);
  }

  void EvaluateWithSensitivities(const core::ModelParameters& params, const std::vector<double>& times,
                                 fitting::ModelOutput* out) const override {
    model_->Evaluate(params, times, out);
    if (!out->ok()) return;
    std::vector<core::SampleSensitivity> d(times.size(), core::SampleSensitivity::Zero());
    fitting::ModelOutput plus, minus;
    // The time column: the same run sampled at t ± h.
    std::vector<double> t_plus = times, t_minus = times;
    for (std::size_t k = 0; k < times.size(); ++k) {
      t_plus[k] += kStep;
      t_minus[k] = std::max(0.0, t_minus[k] - kStep);
    }
    model_->Evaluate(params, t_plus, &plus);
    model_->Evaluate(params, t_minus, &minus);
    if (!plus.ok() || !minus.ok()) return;
    for (std::size_t k = 0; k < times.size(); ++k) {
      d[k].col(static_cast<int>(core::SensitivityColumn::kTime)) = (plus.w_B[k] - minus.w_B[k]) / (t_plus[k] - t_minus[k]);
    }
    const std::array<std::pair<core::SensitivityColumn, double core::ModelParameters::*>, 4> columns = {{
        {core::SensitivityColumn::kAlpha, &core::ModelParameters::alpha_rad},
        {core::SensitivityColumn::kLambda, &core::ModelParameters::lambda},
        {core::SensitivityColumn::kLambdaLat, &core::ModelParameters::lambda_lat},
        {core::SensitivityColumn::kLambdaLon, &core::ModelParameters::lambda_lon},
    }};
    for (const auto& [column, member] : columns) {
      core::ModelParameters p = params, m = params;
      p.*member += kStep;
      m.*member -= kStep;
      model_->Evaluate(p, times, &plus);
      model_->Evaluate(m, times, &minus);
      if (!plus.ok() || !minus.ok()) return;
      for (std::size_t k = 0; k < times.size(); ++k) {
        d[k].col(static_cast<int>(column)) = (plus.w_B[k] - minus.w_B[k]) / (2.0 * kStep);
      }
    }
    out->dw_B_dparams = std::move(d);
  }

  std::string Describe() const override { return model_->Describe() + ", differenced sensitivities"; }

 private:
  std::shared_ptr<const fitting::TrajectoryModel> model_;
};

}  // namespace rockfit::testing
