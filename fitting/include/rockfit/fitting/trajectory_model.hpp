// What the fitter fits: anything that maps model parameters and times after the release to the body-frame
// angular velocity ω_s at those times. The hybrid simulator is one such model (simulator_model.hpp); tests use
// cheap analytic ones. A model must be thread-safe: the global stage evaluates it from several threads at once.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rockfit/core/planar_sensitivity.hpp"
#include "rockfit/core/simulator.hpp"
#include "rockfit/fitting/model_failure.hpp"

namespace rockfit::fitting {

// One impact (or other discrete event) of a model run, in time after the release.
struct ModelEvent {
  double t_s = 0.0;
  core::ImpactKind kind = core::ImpactKind::kFacet;  // as in core::ImpactRecord::kind
};

struct ModelOutput {
  std::vector<Eigen::Vector3d> w_B;  // one per query time [rad/s]; valid only when ok()
  std::vector<ModelEvent> events;    // in time order
  // ∂ω_s/∂(t, α, λ, λ_lat, λ_lon) at each query time (columns as core::SensitivityColumn; NaN where a derivative
  // does not exist). Filled only by EvaluateWithSensitivities, and only where the model can give them exactly;
  // empty otherwise.
  std::vector<core::SampleSensitivity> dw_B_dparams;
  // kNone when the run succeeded. Otherwise why not (with the failing impact's status for an impact failure)
  // and a human-readable detail.
  ModelFailure failure = ModelFailure::kNone;
  core::ImpactStatus impact_status = core::ImpactStatus::kOk;
  std::string failure_detail;
  // Working storage of the model, not output: a model that simulates keeps its trajectory here between runs, so
  // that the runs of one caller (an objective's per-thread output) reuse its vectors. Clear() leaves it alone.
  core::Trajectory scratch_trajectory;
  bool ok() const { return failure == ModelFailure::kNone; }
  std::string failure_category() const { return FailureCategory(failure, impact_status); }
  void Clear() {
    w_B.clear();
    events.clear();
    dw_B_dparams.clear();
    failure = ModelFailure::kNone;
    impact_status = core::ImpactStatus::kOk;
    failure_detail.clear();
  }
};

class TrajectoryModel {
 public:
  virtual ~TrajectoryModel() = default;
  // Fills out->w_B at the ascending times t_after_release_s ≥ 0 (the first is 0, the release), or sets
  // out->failure. Never throws for parameter values a fitter may try; never returns non-finite ω.
  virtual void Evaluate(const core::ModelParameters& params, const std::vector<double>& t_after_release_s,
                        ModelOutput* out) const = 0;
  // Evaluate, plus the exact derivatives of ω_s in out->dw_B_dparams where the model has them (left empty where
  // it has none: the default, and runs the model cannot differentiate).
  virtual void EvaluateWithSensitivities(const core::ModelParameters& params,
                                         const std::vector<double>& t_after_release_s, ModelOutput* out) const {
    Evaluate(params, t_after_release_s, out);
  }
  // One line for summaries ("hybrid simulator, rel_tol 1e-10", …).
  virtual std::string Describe() const = 0;
  // A copy that integrates with the relative tolerance rel_tol where that is looser than its own (for searches that
  // only need the basin); null when the model has no tolerance to loosen.
  virtual std::shared_ptr<const TrajectoryModel> WithLooserTolerance(double /*rel_tol*/) const { return nullptr; }
};

}  // namespace rockfit::fitting
