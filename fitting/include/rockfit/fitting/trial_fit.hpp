// Fitting one recorded trial end to end: estimate the start from the data (data_estimate.hpp), remove the
// gyro bias measured at rest, set the window [t0, t_end], fit with the hybrid simulator (or another model),
// and sample the result for plots and the HDF5 store. Also ε (28) of given parameters (`rockfit fit --evaluate`).
#pragma once

#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "rockfit/core/block.hpp"
#include "rockfit/fitting/data_estimate.hpp"
#include "rockfit/fitting/fit_options.hpp"
#include "rockfit/fitting/fit_summary.hpp"
#include "rockfit/fitting/simulator_model.hpp"
#include "rockfit/fitting/trajectory_error.hpp"
#include "rockfit/fitting/trajectory_model.hpp"

namespace rockfit::fitting {

struct TrialFitOptions {
  FitOptions fit;
  EstimateOptions estimate;
  SimulatorModelOptions simulation;
  std::optional<double> t_end_s;   // given end of the window (recording time); otherwise detected
  bool subtract_rest_bias = true;  // remove the gyro bias measured at rest before the release
  // Starting values that replace the data estimate for these parameters (`rockfit fit --start`).
  std::vector<std::pair<ParameterId, double>> start_values;
  void Validate() const;           // throws InvalidArgument
};

// The model at a parameter set, sampled at the measured times in the window, for plots and the store.
struct SimulatedTrace {
  std::vector<double> t_s;             // recording time, the measured samples in [t0, t_end]
  std::vector<Eigen::Vector3d> w_B;    // ω_s [rad/s]
  std::vector<ModelEvent> events;      // impacts in recording time, up to t_end
  bool ok = false;
  std::string failure;
};

struct TrialFit {
  FitSummary summary;
  DataEstimate estimate;
  MeasuredSignal signal;  // as fitted: bias removed when requested
  SimulatedTrace trace;   // at summary.parameters
};

// `model` defaults to the hybrid simulator with options.simulation. Throws BadInput when the recording cannot be
// fitted (no impact, too few impacts for the window), InvalidArgument for bad options or parameters.
TrialFit FitTrial(const core::Block& block, const MeasuredSignal& recorded, const ParameterSet& parameters,
                  const TrialFitOptions& options, std::shared_ptr<const TrajectoryModel> model = nullptr);

struct TrialEvaluation {
  double epsilon_rad_s = 0.0;
  bool feasible = false;
  std::string failure;
  double t_end_s = 0.0;
  DataEstimate estimate;  // window and bias (the parameter values are the given ones)
  MeasuredSignal signal;
  SimulatedTrace trace;
};
// ε (28) at the values of the fixed parameters of `parameters` and the data's estimate of the free ones, on the
// same window and bias-corrected signal a fit would use.
TrialEvaluation EvaluateTrial(const core::Block& block, const MeasuredSignal& recorded, const ParameterSet& parameters,
                              const TrialFitOptions& options, std::shared_ptr<const TrajectoryModel> model = nullptr);

// The trace of `model` at `parameters` on `signal` up to t_end.
SimulatedTrace TraceAt(const TrajectoryModel& model, const MeasuredSignal& signal, const ParameterSet& parameters,
                       double t_end_s);

}  // namespace rockfit::fitting
