#include "rockfit/fitting/trial_problem.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/rest_noise.hpp"

namespace rockfit::fitting {

void TrialProblemOptions::Validate() const {
  guess.Validate();
  clipping.Validate();
  release_roll.Validate();
  for (double v : {rest_margin_s, rest_min_duration_s, window_end_margin_s}) {
    if (!(std::isfinite(v) && v >= 0.0)) {
      throw InvalidArgument(fmt::format("trial problem options: durations must be non-negative seconds, got {}", v));
    }
  }
  if (t_end_s && !std::isfinite(*t_end_s)) throw InvalidArgument("--t-end must be a finite time in seconds");
}

TrialProblem PrepareTrialProblem(const MeasuredSignal& recorded, const core::Block& block,
                                 const ParameterSet& parameters, const TrialProblemOptions& options,
                                 std::shared_ptr<const TrajectoryModel> model) {
  options.Validate();
  recorded.Validate();
  MeasuredSignal signal = recorded;
  std::vector<std::string> notes;
  // The gyro's rail, on the recorded values (a bias subtracted per axis would move the three axes' rails apart).
  GyroClipping clipping = DetectGyroClipping(signal, options.clipping);
  if (clipping.detected) {
    signal.excluded = clipping.clipped;
    if (options.clipping.censored) signal.censored_axes = clipping.axes;
    notes.push_back(fmt::format("{} sample(s) at the gyro's full scale ±{:.4g} rad/s (clipped) {}", clipping.samples,
                                clipping.level_rad_s,
                                options.clipping.censored ? "enter (28) as censored: \"at least this fast\""
                                                          : "are left out of (28)"));
  }
  InitialGuess guess = EstimateInitialGuess(signal, block, parameters, options.guess);

  // The gyro bias at rest, then the estimate again on the corrected signal.
  Eigen::Vector3d bias = Eigen::Vector3d::Zero();
  bool subtracted = false;
  if (options.subtract_rest_bias) {
    const RestNoise rest = MeasureRestNoise(signal, guess.parameters.value(ParameterId::kT0),
                                            {options.rest_margin_s, options.rest_min_duration_s});
    if (rest.available) {
      bias = rest.mean_rad_s;
      for (Eigen::Vector3d& w : signal.w_B) w -= bias;
      subtracted = true;
      guess = EstimateInitialGuess(signal, block, parameters, options.guess);
      notes.push_back(fmt::format("gyro bias at rest over {:.2f} s before the release: ({:.4f}, {:.4f}, {:.4f}) rad/s, "
                                  "subtracted",
                                  rest.duration_s, bias.x(), bias.y(), bias.z()));
    } else {
      notes.push_back("gyro bias not measured: the recording starts too close to the release");
    }
  }
  notes.insert(notes.begin(), guess.notes.begin(), guess.notes.end());

  ParameterSet start = guess.parameters;
  // The release roll: fitted when asked (freed by the caller) or, in auto, when the fall shows one.
  const Parameter& given_roll = parameters[ParameterId::kReleaseRoll];
  ReleaseRollChoiceOptions roll_options = options.release_roll;
  if (!given_roll.fixed) roll_options.mode = ReleaseRollMode::kOn;
  else if (given_roll.value != 0.0) roll_options.mode = ReleaseRollMode::kOff;
  const ReleaseRollChoice roll = ChooseReleaseRoll(signal, guess.parameters.value(ParameterId::kT0),
                                                   guess.t_first_impact_s, roll_options);
  if (roll.fitted) {
    Parameter& beta = start[ParameterId::kReleaseRoll];
    beta.fixed = false;
    if (given_roll.fixed || given_roll.value == 0.0) beta.value = std::clamp(roll.start_rad, beta.lower, beta.upper);
  }
  Parameter& t0 = start[ParameterId::kT0];
  if (!std::isfinite(t0.lower)) t0.lower = signal.t_s.front();
  if (!std::isfinite(t0.upper)) t0.upper = guess.t_first_impact_s;
  t0.value = std::clamp(t0.value, t0.lower, t0.upper);
  start.Validate();

  double t_end = guess.t_end_s;
  if (options.t_end_s) {
    t_end = *options.t_end_s;
  } else if (options.window_end_margin_s > 0.0) {
    // Keep the end after the first impact whatever the margin.
    t_end = std::max(guess.t_end_s - options.window_end_margin_s, 0.5 * (guess.t_end_s + guess.t_first_impact_s));
  }
  if (!(t_end > start.value(ParameterId::kT0) && t_end <= signal.t_s.back())) {
    throw InvalidArgument(fmt::format("--t-end {} s must lie after the release (t0 ≈ {:.4f} s) and inside the "
                                      "recording (ends at {:.4f} s)",
                                      t_end, start.value(ParameterId::kT0), signal.t_s.back()));
  }
  if (!model) model = std::make_shared<SimulatorModel>(block);
  // The later window ends, each the margin before a later return impact; a given window is not extended.
  std::vector<double> later_ends;
  if (!options.t_end_s) {
    for (double t_impact : guess.later_impacts_s) {
      const double t = std::min(t_impact - options.window_end_margin_s, signal.t_s.back());
      if (t > (later_ends.empty() ? t_end : later_ends.back())) later_ends.push_back(t);
    }
  }
  Objective objective =
      Objective(std::move(signal), t_end, std::move(model), start).WithLaterWindowEnds(std::move(later_ends));
  return TrialProblem{std::move(objective), std::move(start), std::move(guess), bias, subtracted, std::move(clipping),
                      roll, std::move(notes)};
}

}  // namespace rockfit::fitting
