#include "rockfit/fitting/trial_fit.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/fitter.hpp"
#include "rockfit/fitting/objective.hpp"

namespace rockfit::fitting {
namespace {

// ε above this fraction of the mean measured |ω| over the window is reported as a poor fit. Fits of rocking
// trials reach 1–3 % (the gyro's noise and ringing); a wrong block, mounting or window gives tens of percent.
constexpr double kPoorFitFraction = 0.2;

struct Prepared {
  DataEstimate estimate;
  MeasuredSignal signal;
  double t_end_s = 0.0;
  std::shared_ptr<const TrajectoryModel> model;
};

Prepared Prepare(const core::Block& block, const MeasuredSignal& recorded, const ParameterSet& parameters,
                 const TrialFitOptions& options, std::shared_ptr<const TrajectoryModel> model) {
  options.Validate();
  recorded.Validate();
  parameters.Validate();
  Prepared p;
  EstimateOptions estimate_options = options.estimate;
  p.estimate = EstimateFromData(block, recorded, parameters, estimate_options);
  p.signal = recorded;
  if (options.subtract_rest_bias && p.estimate.bias_estimated) {
    for (Eigen::Vector3d& w : p.signal.w_B) w -= p.estimate.rest_bias_rad_s;
  }
  p.t_end_s = options.t_end_s.value_or(p.estimate.t_end_s);
  if (options.t_end_s) {
    if (!(*options.t_end_s > recorded.t_s.front() && *options.t_end_s <= recorded.t_s.back())) {
      throw InvalidArgument(fmt::format("--t-end {} s lies outside the recording ({} s to {} s)", *options.t_end_s,
                                        recorded.t_s.front(), recorded.t_s.back()));
    }
    p.estimate.t_end_s = *options.t_end_s;
  }
  // t0 must stay before t_end.
  Parameter& t0 = p.estimate.parameters[ParameterId::kT0];
  if (!t0.fixed) {
    t0.upper = std::min(t0.upper, p.t_end_s - 1e-3);
    t0.lower = std::min(t0.lower, t0.upper - 1e-3);
    t0.value = std::clamp(t0.value, t0.lower, t0.upper);
  }
  p.model = model ? std::move(model) : std::make_shared<SimulatorModel>(block, options.simulation);
  return p;
}

}  // namespace

void TrialFitOptions::Validate() const {
  for (const auto& [id, value] : start_values) {
    if (!std::isfinite(value)) throw InvalidArgument(fmt::format("the start value of {} must be finite", Name(id)));
  }
  fit.Validate();
  estimate.Validate();
  simulation.Validate();
}

SimulatedTrace TraceAt(const TrajectoryModel& model, const MeasuredSignal& signal, const ParameterSet& parameters,
                       double t_end_s) {
  SimulatedTrace trace;
  const double t0 = parameters.value(ParameterId::kT0);
  std::vector<double> after_release = {0.0};
  trace.t_s.push_back(t0);
  for (std::size_t k = 0; k < signal.size(); ++k) {
    if (signal.t_s[k] > t0 && signal.t_s[k] <= t_end_s) {
      trace.t_s.push_back(signal.t_s[k]);
      after_release.push_back(signal.t_s[k] - t0);
    }
  }
  ModelOutput out;
  model.Evaluate(parameters.ToModel(), after_release, &out);
  trace.ok = out.ok();
  trace.failure = out.failure;
  if (!out.ok()) {
    trace.t_s.clear();
    return trace;
  }
  trace.w_B = out.w_B;
  for (const ModelEvent& e : out.events) {
    if (t0 + e.t_s <= t_end_s) trace.events.push_back({t0 + e.t_s, e.kind});
  }
  return trace;
}

TrialFit FitTrial(const core::Block& block, const MeasuredSignal& recorded, const ParameterSet& parameters,
                  const TrialFitOptions& options, std::shared_ptr<const TrajectoryModel> model) {
  Prepared p = Prepare(block, recorded, parameters, options, std::move(model));
  ParameterSet start = p.estimate.parameters;  // the data's estimate, in the data's t0 bounds
  if (!options.fit.start_from_data) {
    for (ParameterId id : kAllParameters) {
      if (id != ParameterId::kT0 || std::isfinite(parameters[id].lower)) start[id].value = parameters.value(id);
    }
  }
  for (const auto& [id, value] : options.start_values) start[id].value = value;
  const Objective objective(p.signal, p.t_end_s, p.model, p.estimate.parameters);
  TrialFit fit;
  fit.summary = Fit(objective, start, options.fit);
  for (const std::string& w : p.estimate.warnings) fit.summary.warnings.push_back({"data", "", w});
  // A fit whose mean error is a large part of the motion itself does not describe the recording.
  if (fit.summary.feasible) {
    ErrorNodes nodes;
    const bool window_ok = BuildErrorNodes(p.signal, fit.summary.parameters.value(ParameterId::kT0), p.t_end_s, &nodes);
    double mean_rate = 0.0;
    if (window_ok) mean_rate = TrajectoryError(nodes, std::vector<Eigen::Vector3d>(nodes.size(), Eigen::Vector3d::Zero()));
    if (window_ok && fit.summary.epsilon_rad_s > kPoorFitFraction * mean_rate) {
      fit.summary.warnings.push_back(
          {"poor_fit", "",
           fmt::format("ε is {:.0f} % of the mean measured |ω| ({:.3g} rad/s) in the window: the model does not describe "
                       "this recording; check the block size, the mounting and the window",
                       100.0 * fit.summary.epsilon_rad_s / mean_rate, mean_rate)});
    }
  }
  fit.trace = TraceAt(*p.model, p.signal, fit.summary.parameters, p.t_end_s);
  fit.estimate = std::move(p.estimate);
  fit.signal = std::move(p.signal);
  return fit;
}

TrialEvaluation EvaluateTrial(const core::Block& block, const MeasuredSignal& recorded, const ParameterSet& parameters,
                              const TrialFitOptions& options, std::shared_ptr<const TrajectoryModel> model) {
  Prepared p = Prepare(block, recorded, parameters, options, std::move(model));
  // Fixed parameters keep the caller's values; the estimate fills the free ones.
  const ParameterSet values = p.estimate.parameters;
  ParameterSet all_fixed = values;  // nothing is fitted: bounds do not apply
  for (ParameterId id : kAllParameters) all_fixed[id].fixed = true;
  const Objective objective(p.signal, p.t_end_s, p.model, all_fixed);
  const Evaluation e = objective.Evaluate(values);
  TrialEvaluation result;
  result.epsilon_rad_s = e.epsilon_rad_s;
  result.feasible = e.feasible;
  result.failure = e.failure;
  result.t_end_s = p.t_end_s;
  result.trace = TraceAt(*p.model, p.signal, values, p.t_end_s);
  result.estimate = std::move(p.estimate);
  result.signal = std::move(p.signal);
  return result;
}

}  // namespace rockfit::fitting
