// The fitting problem of one trial: the measured signal, the end of the fitting window t_end, a trajectory
// model and the parameter set (values of fixed parameters, bounds of free ones). Evaluates the error (28) at
// any parameter vector; a model failure makes the point infeasible: ε is replaced by a large finite penalty
// and the failure is counted by its reason. Immutable apart from the thread-safe evaluation counters.
#pragma once

#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rockfit/fitting/gyro_scale.hpp"
#include "rockfit/fitting/parameters.hpp"
#include "rockfit/fitting/trajectory_error.hpp"
#include "rockfit/fitting/trajectory_model.hpp"

namespace rockfit::fitting {

// Counts model runs and failures; shared by copies of an Objective, safe to update from several threads.
class EvaluationCounters {
 public:
  void CountRun() { runs_.fetch_add(1, std::memory_order_relaxed); }
  void CountFailure(const std::string& reason);
  std::int64_t runs() const { return runs_.load(std::memory_order_relaxed); }
  std::int64_t failures() const;
  std::map<std::string, std::int64_t> failures_by_reason() const;

 private:
  std::atomic<std::int64_t> runs_{0};
  mutable std::mutex mutex_;
  std::map<std::string, std::int64_t> failures_;
};

struct ObjectiveOptions {
  // ε assigned to an infeasible point [rad/s]: far above any real ε (the measured |ω| of a rocking block
  // stays below ~20 rad/s), finite so that optimizers keep working.
  double failure_penalty_rad_s = 1e3;
  // The gyro scale projected out of every evaluation (gyro_scale.hpp): (28) is then of the scaled model S·ω_s.
  GyroScaleMode gyro_scale = GyroScaleMode::kOff;
  void Validate() const;  // throws InvalidArgument
};

// The outcome of one evaluation.
struct Evaluation {
  double epsilon_rad_s = 0.0;  // (28), or the penalty when infeasible
  bool feasible = false;
  ModelFailure failure = ModelFailure::kNone;                  // why not feasible
  core::ImpactStatus impact_status = core::ImpactStatus::kOk;  // the failing impact's status, if any
  // The projected gyro scale S (diagonal) of this evaluation; (1, 1, 1) when the objective estimates none.
  Eigen::Vector3d gyro_scale = Eigen::Vector3d::Ones();
  std::string failure_category() const { return FailureCategory(failure, impact_status); }  // "" when feasible
};

class Objective {
 public:
  // Validates every argument (InvalidArgument): the signal, t_end inside the recording, the parameter set.
  Objective(MeasuredSignal signal, double t_end_s, std::shared_ptr<const TrajectoryModel> model,
            ParameterSet parameters, ObjectiveOptions options = {});

  // The same problem (signal, window, model, shared counters) with other fixed flags, values or bounds.
  Objective WithParameters(ParameterSet parameters) const;
  // The same problem with the window ending at another t_end (inside the recording, InvalidArgument otherwise).
  // The later window ends after it are kept.
  Objective WithWindowEnd(double t_end_s) const;
  // The same problem with later ends that the window may be extended to (window_extension.hpp): increasing,
  // after t_end and inside the recording (InvalidArgument otherwise). A prepared trial gives the times just
  // before the return impacts after the one that ends its window; a given t_end gives none.
  Objective WithLaterWindowEnds(std::vector<double> later_t_end_s) const;
  // The same problem (and shared counters) with another trajectory model, e.g. one at a looser tolerance.
  Objective WithModel(std::shared_ptr<const TrajectoryModel> model) const;
  // The same problem (and shared counters) with the gyro scale projected out as `mode` says (gyro_scale.hpp).
  Objective WithGyroScale(GyroScaleMode mode) const;

  const MeasuredSignal& signal() const { return *signal_; }
  double t_end_s() const { return t_end_s_; }
  const std::vector<double>& later_window_ends_s() const { return later_window_ends_s_; }
  const TrajectoryModel& model() const { return *model_; }
  const ParameterSet& parameters() const { return parameters_; }
  const std::vector<ParameterId>& free_ids() const { return free_ids_; }
  std::size_t num_free() const { return free_ids_.size(); }
  bool IsFree(ParameterId id) const { return !parameters_[id].fixed; }  // one of free_ids()
  const ObjectiveOptions& options() const { return options_; }
  EvaluationCounters& counters() const { return *counters_; }

  // The parameter set with the free parameters replaced by x (in the order of free_ids()).
  ParameterSet WithFree(const Eigen::VectorXd& x) const;
  // The free values of a parameter set, in the order of free_ids().
  Eigen::VectorXd FreeValues(const ParameterSet& set) const;
  Eigen::VectorXd FreeLower() const;
  Eigen::VectorXd FreeUpper() const;

  // (28) at a full parameter set (bounds are not enforced here).
  Evaluation Evaluate(const ParameterSet& values) const;
  Evaluation EvaluateFree(const Eigen::VectorXd& x) const { return Evaluate(WithFree(x)); }

  // The nodes of (28) and the model output at them (for residual-based back ends, plots, diagnostics).
  // Returns the evaluation; `nodes` and `output` are filled as far as the evaluation got.
  // With `sensitivities`, the model is asked for the exact derivatives of ω_s too (ModelOutput::dw_B_dparams).
  // With a gyro scale, output->w_B is the scaled model S·ω_s, and the exact derivatives are dropped (they would
  // miss the scale's own dependence on the parameters; the residuals are then differenced).
  Evaluation EvaluateDetailed(const ParameterSet& values, ErrorNodes* nodes, ModelOutput* output,
                              bool sensitivities = false) const;

  // (28) on `nodes`, built by BuildErrorNodes from this signal for the t0 of `values` and an end inside the
  // recording: the evaluation WithWindowEnd(that end).Evaluate(values) gives, without copying the problem or
  // building the nodes again (the prefix screen's shorter windows, prefix_screen.hpp).
  Evaluation EvaluateOnNodes(const ParameterSet& values, const ErrorNodes& nodes) const;

 private:
  // An infeasible evaluation for `reason`, counted.
  Evaluation Infeasible(ModelFailure reason, core::ImpactStatus impact_status = core::ImpactStatus::kOk) const;
  // EvaluateDetailed from the nodes on (they are built): runs the model into *output and evaluates (28).
  Evaluation EvaluateBuilt(const ParameterSet& values, const ErrorNodes& nodes, ModelOutput* output,
                           bool sensitivities) const;

  std::shared_ptr<const MeasuredSignal> signal_;
  double t_end_s_;
  std::vector<double> later_window_ends_s_;
  std::shared_ptr<const TrajectoryModel> model_;
  ParameterSet parameters_;
  std::vector<ParameterId> free_ids_;
  ObjectiveOptions options_;
  std::shared_ptr<EvaluationCounters> counters_;
};

}  // namespace rockfit::fitting
