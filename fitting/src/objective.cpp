#include "rockfit/fitting/objective.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::fitting {
namespace {

bool AllFinite(const ParameterSet& values) {
  for (ParameterId id : kAllParameters) {
    if (!std::isfinite(values.value(id))) return false;
  }
  return true;
}

}  // namespace

void EvaluationCounters::CountFailure(const std::string& reason) {
  std::lock_guard<std::mutex> lock(mutex_);
  ++failures_[reason];
}

std::int64_t EvaluationCounters::failures() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::int64_t total = 0;
  for (const auto& entry : failures_) total += entry.second;
  return total;
}

std::map<std::string, std::int64_t> EvaluationCounters::failures_by_reason() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return failures_;
}

void ObjectiveOptions::Validate() const {
  if (!(std::isfinite(failure_penalty_rad_s) && failure_penalty_rad_s > 0.0)) {
    throw InvalidArgument(
        fmt::format("failure_penalty_rad_s must be a positive finite number, got {}", failure_penalty_rad_s));
  }
}

Objective::Objective(MeasuredSignal signal, double t_end_s, std::shared_ptr<const TrajectoryModel> model,
                     ParameterSet parameters, ObjectiveOptions options)
    : signal_(std::make_shared<const MeasuredSignal>(std::move(signal))),
      t_end_s_(t_end_s),
      model_(std::move(model)),
      parameters_(std::move(parameters)),
      free_ids_(parameters_.FreeIds()),
      options_(options),
      counters_(std::make_shared<EvaluationCounters>()) {
  signal_->Validate();
  options_.Validate();
  parameters_.Validate();
  if (!model_) throw InvalidArgument("the fitting problem needs a trajectory model");
  if (!(std::isfinite(t_end_s_) && t_end_s_ > signal_->t_s.front() && t_end_s_ <= signal_->t_s.back())) {
    throw InvalidArgument(fmt::format("t_end = {} s lies outside the recording ({} s to {} s)", t_end_s_,
                                      signal_->t_s.front(), signal_->t_s.back()));
  }
}

Objective Objective::WithParameters(ParameterSet parameters) const {
  parameters.Validate();
  Objective copy = *this;
  copy.parameters_ = std::move(parameters);
  copy.free_ids_ = copy.parameters_.FreeIds();
  return copy;
}

Objective Objective::WithWindowEnd(double t_end_s) const {
  if (!(std::isfinite(t_end_s) && t_end_s > signal_->t_s.front() && t_end_s <= signal_->t_s.back())) {
    throw InvalidArgument(fmt::format("t_end = {} s lies outside the recording ({} s to {} s)", t_end_s,
                                      signal_->t_s.front(), signal_->t_s.back()));
  }
  Objective copy = *this;
  copy.t_end_s_ = t_end_s;
  auto& later = copy.later_window_ends_s_;
  later.erase(later.begin(), std::upper_bound(later.begin(), later.end(), t_end_s));
  return copy;
}

Objective Objective::WithLaterWindowEnds(std::vector<double> later_t_end_s) const {
  double previous = t_end_s_;
  for (double t : later_t_end_s) {
    if (!(std::isfinite(t) && t > previous && t <= signal_->t_s.back())) {
      throw InvalidArgument(fmt::format("a later window end {} s must lie after the previous end ({} s) and inside "
                                        "the recording (ends at {} s)",
                                        t, previous, signal_->t_s.back()));
    }
    previous = t;
  }
  Objective copy = *this;
  copy.later_window_ends_s_ = std::move(later_t_end_s);
  return copy;
}

Objective Objective::WithGyroScale(GyroScaleMode mode) const {
  Objective copy = *this;
  copy.options_.gyro_scale = mode;
  return copy;
}

Objective Objective::WithModel(std::shared_ptr<const TrajectoryModel> model) const {
  if (!model) throw InvalidArgument("the fitting problem needs a trajectory model");
  Objective copy = *this;
  copy.model_ = std::move(model);
  return copy;
}

ParameterSet Objective::WithFree(const Eigen::VectorXd& x) const {
  ParameterSet set = parameters_;
  for (std::size_t i = 0; i < free_ids_.size(); ++i) set[free_ids_[i]].value = x[static_cast<Eigen::Index>(i)];
  return set;
}

Eigen::VectorXd Objective::FreeValues(const ParameterSet& set) const {
  Eigen::VectorXd x(static_cast<Eigen::Index>(free_ids_.size()));
  for (std::size_t i = 0; i < free_ids_.size(); ++i) x[static_cast<Eigen::Index>(i)] = set.value(free_ids_[i]);
  return x;
}

Eigen::VectorXd Objective::FreeLower() const {
  Eigen::VectorXd x(static_cast<Eigen::Index>(free_ids_.size()));
  for (std::size_t i = 0; i < free_ids_.size(); ++i) x[static_cast<Eigen::Index>(i)] = parameters_[free_ids_[i]].lower;
  return x;
}

Eigen::VectorXd Objective::FreeUpper() const {
  Eigen::VectorXd x(static_cast<Eigen::Index>(free_ids_.size()));
  for (std::size_t i = 0; i < free_ids_.size(); ++i) x[static_cast<Eigen::Index>(i)] = parameters_[free_ids_[i]].upper;
  return x;
}

Evaluation Objective::Evaluate(const ParameterSet& values) const {
  // Scratch reused by each thread, so that repeated evaluations do not allocate.
  thread_local ErrorNodes nodes;
  thread_local ModelOutput output;
  return EvaluateDetailed(values, &nodes, &output);
}

Evaluation Objective::EvaluateOnNodes(const ParameterSet& values, const ErrorNodes& nodes) const {
  thread_local ModelOutput output;  // as in Evaluate
  output.Clear();
  if (!AllFinite(values)) return Infeasible(ModelFailure::kNonFiniteParameter);
  return EvaluateBuilt(values, nodes, &output, false);
}

Evaluation Objective::Infeasible(ModelFailure reason, core::ImpactStatus impact_status) const {
  Evaluation result;
  result.feasible = false;
  result.failure = reason;
  result.impact_status = impact_status;
  counters_->CountFailure(result.failure_category());
  result.epsilon_rad_s = options_.failure_penalty_rad_s;
  return result;
}

Evaluation Objective::EvaluateDetailed(const ParameterSet& values, ErrorNodes* nodes, ModelOutput* output,
                                       bool sensitivities) const {
  output->Clear();
  if (!AllFinite(values)) return Infeasible(ModelFailure::kNonFiniteParameter);
  const double t0 = values.value(ParameterId::kT0);
  if (!BuildErrorNodes(*signal_, t0, t_end_s_, nodes)) return Infeasible(ModelFailure::kT0OutsideWindow);
  return EvaluateBuilt(values, *nodes, output, sensitivities);
}

Evaluation Objective::EvaluateBuilt(const ParameterSet& values, const ErrorNodes& nodes, ModelOutput* output,
                                    bool sensitivities) const {
  if (nodes.num_excluded == nodes.size() || !(nodes.weighted_duration_s() > 0.0)) {
    return Infeasible(ModelFailure::kAllSamplesClipped);
  }

  counters_->CountRun();
  if (sensitivities) {
    model_->EvaluateWithSensitivities(values.ToModel(), nodes.t_after_release_s, output);
  } else {
    model_->Evaluate(values.ToModel(), nodes.t_after_release_s, output);
  }
  if (!output->ok()) return Infeasible(output->failure, output->impact_status);
  if (output->w_B.size() != nodes.size()) {
    return Infeasible(ModelFailure::kWrongSampleCount);
  }
  Evaluation result;
  if (options_.gyro_scale != GyroScaleMode::kOff) {
    // Variable projection (gyro_scale.hpp): the best S for these parameters, and (28) of S·ω_s.
    result.gyro_scale = ProjectedGyroScale(nodes, output->w_B, options_.gyro_scale);
    for (Eigen::Vector3d& w : output->w_B) w = result.gyro_scale.cwiseProduct(w);
    output->dw_B_dparams.clear();
  }
  const double epsilon = TrajectoryError(nodes, output->w_B);  // (28)
  if (!std::isfinite(epsilon)) {
    Evaluation failed = Infeasible(ModelFailure::kNonFiniteOutput);
    failed.gyro_scale = result.gyro_scale;  // the scale that was projected, as before the failure
    return failed;
  }
  result.feasible = true;
  result.epsilon_rad_s = epsilon;
  return result;
}

}  // namespace rockfit::fitting
