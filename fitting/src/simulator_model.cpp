#include "rockfit/fitting/simulator_model.hpp"

#include <algorithm>
#include <exception>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/core/planar_sensitivity.hpp"
#include "rockfit/core/spatial_sensitivity.hpp"

namespace rockfit::fitting {
namespace {

// Impacts allowed in one fitting run; the paper's Fig. 14 window has about 25.
constexpr std::size_t kMaxImpactsPerRun = 5000;

}  // namespace

core::SimulationOptions SimulatorModelOptions::DefaultFittingSimulation() {
  core::SimulationOptions o;
  o.max_impacts = kMaxImpactsPerRun;
  o.sample_attitude = false;
  return o;
}

void SimulatorModelOptions::Validate() const {
  core::SimulationOptions probe = simulation;
  probe.sample_times_s.clear();
  probe.stop = core::StopCondition::kTMax;
  probe.Validate();
  if (simulation.initial_state) {
    throw InvalidArgument("fitting starts every run from the release at tilt alpha; remove the initial state");
  }
}

SimulatorModel::SimulatorModel(const core::Block& block, SimulatorModelOptions options)
    : block_(block), options_(std::move(options)) {
  options_.Validate();
}

void SimulatorModel::Evaluate(const core::ModelParameters& params, const std::vector<double>& times,
                              ModelOutput* out) const {
  Run(params, times, false, out);
}

void SimulatorModel::EvaluateWithSensitivities(const core::ModelParameters& params, const std::vector<double>& times,
                                               ModelOutput* out) const {
  Run(params, times, true, out);
}

void SimulatorModel::Run(const core::ModelParameters& params, const std::vector<double>& times, bool sensitivities,
                         ModelOutput* out) const {
  out->Clear();
  if (times.empty()) return;
  // Per-thread options, so that the sample-time vector keeps its storage between runs.
  thread_local core::SimulationOptions run;
  run = options_.simulation;
  run.sample_times_s.assign(times.begin(), times.end());
  run.stop = core::StopCondition::kTMax;
  run.t_max_s = std::max(times.back(), 1e-9);
  run.sample_attitude = false;
  core::Trajectory& trajectory = out->scratch_trajectory;
  try {
    core::SimulateInto(block_, params, run, &trajectory);
  } catch (const InvalidArgument& e) {
    out->failure = ModelFailure::kInvalidParameters;
    out->failure_detail = e.what();
    return;
  } catch (const std::exception& e) {
    out->failure = ModelFailure::kSimulatorException;
    out->failure_detail = e.what();
    return;
  }
  switch (trajectory.end_reason) {
    case core::EndReason::kOverturned:
      out->failure = ModelFailure::kOverturned;
      out->failure_detail = fmt::format("the block overturns at t = {:.4f} s after the release", trajectory.t_end_s);
      return;
    case core::EndReason::kFailed:
      // The failing impact, if any, is the last of the log.
      out->impact_status = trajectory.impacts.empty() ? core::ImpactStatus::kOk : trajectory.impacts.back().status;
      out->failure = FromSimulation(trajectory.failure, out->impact_status);
      if (out->failure == ModelFailure::kFailed) out->impact_status = core::ImpactStatus::kOk;
      out->failure_detail = trajectory.message;
      return;
    default:
      break;
  }
  if (trajectory.w_B.size() != times.size()) {
    out->failure = ModelFailure::kIncompleteRun;
    out->failure_detail = fmt::format("the run ended ({}) at t = {:.4f} s with {} of {} samples",
                                      core::ToString(trajectory.end_reason), trajectory.t_end_s, trajectory.w_B.size(),
                                      times.size());
    return;
  }
  if (sensitivities) {
    // λ_lat = 0 keeps a release planar (planar_sensitivity.hpp); otherwise the run is 3D (spatial_sensitivity.hpp).
    if (params.lambda_lat == 0.0) {
      core::PlanarSensitivitySummary planar = core::PlanarSampleSensitivities(block_, params, run, trajectory);
      if (planar.available) out->dw_B_dparams = std::move(planar.dw_B);
    } else {
      core::SpatialSensitivitySummary spatial = core::SpatialSampleSensitivities(block_, params, run, trajectory);
      if (spatial.available) out->dw_B_dparams = std::move(spatial.dw_B);
    }
  }
  out->w_B.swap(trajectory.w_B);  // the scratch gets out's old storage for the next run
  out->events.reserve(trajectory.impacts.size());
  for (const core::ImpactRecord& impact : trajectory.impacts) out->events.push_back({impact.t_s, impact.kind});
}

std::shared_ptr<const TrajectoryModel> SimulatorModel::WithLooserTolerance(double rel_tol) const {
  SimulatorModelOptions loose = options_;
  // The absolute tolerance keeps the default ratio (1e-14 to 1e-12): ω and the quaternion are of order one.
  constexpr double kAbsoluteToRelative = 1e-2;
  loose.simulation.rel_tol = std::max(options_.simulation.rel_tol, rel_tol);
  loose.simulation.abs_tol = std::max(options_.simulation.abs_tol, kAbsoluteToRelative * rel_tol);
  return std::make_shared<const SimulatorModel>(block_, loose);
}

std::string SimulatorModel::Describe() const {
  return fmt::format("hybrid simulator, rel_tol {:g}, abs_tol {:g}", options_.simulation.rel_tol,
                     options_.simulation.abs_tol);
}

}  // namespace rockfit::fitting
