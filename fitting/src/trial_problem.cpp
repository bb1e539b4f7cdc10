#include "rockfit/fitting/trial_problem.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/rest_noise.hpp"

namespace rockfit::fitting {
namespace {

// The closed-form phase-1 fit's t0 agrees with the default's (RK4 nodes, golden sections) to 3.7e-9 s on the 16
// sample trials (initial_guess.hpp, closed_form_fall; the tests allow 1e-8 s on synthetic ones); its rest segment is
// used only when every t0 within this distance of it places the same one: 270 times the largest difference measured,
// and far below a sample period (3.9 ms at 256 Hz), so that the fallback to the default fit is rare.
constexpr double kReleaseRoundOffS = 1e-6;
// Either phase-1 fit puts the landing t0 + T(α) at most 1.5 sample periods after the first impact's peak (t0 is
// searched within 1.5 periods of the peak less the fall table's end, which is at or after T(α)). With a usable
// sample this many periods after the peak, neither finds the recording ending at the impact (half a period spare).
constexpr double kPeriodsAfterPeak = 2.0;

// The duration of the rest segment as the note shows it.
std::string RestDurationText(double duration_s) { return fmt::format("{:.2f}", duration_s); }

}  // namespace

std::optional<RestNoise> RestBeforeClosedFormRelease(const MeasuredSignal& signal, const core::Block& block,
                                                     const ParameterSet& parameters, const TrialProblemOptions& options) {
  InitialGuessOptions closed_form = options.guess;
  closed_form.closed_form_fall = true;
  const ReleaseEstimate release = EstimateRelease(signal, block, parameters, closed_form);
  // The default estimate looks at the samples after its landing (the first jump) and fails without one.
  const double period_s = (signal.t_s.back() - signal.t_s.front()) / static_cast<double>(signal.size() - 1);
  const double t_sure_after_s = release.t_first_impact_s + kPeriodsAfterPeak * period_s;
  bool sample_after = false;
  for (std::size_t k = signal.size(); k-- > 0 && signal.t_s[k] > t_sure_after_s;) {
    if (!signal.is_excluded(k)) {
      sample_after = true;
      break;
    }
  }
  if (!sample_after) return std::nullopt;
  // Everything the rest segment passes on is a monotone function of t0: its end (t0 − margin, or the margin before
  // the onset of a motion that runs into t0, which moves only forward as t0 does: rest_noise.hpp), the samples
  // before that end (their mean is the bias), its duration end − t_first (floating-point subtraction is monotone),
  // hence its comparison with the minimum and its rounding to the note's 2 decimals. The same at both ends of [t0 − δ, t0 + δ] is the
  // same at the default fit's t0, which lies inside.
  const RestSegmentOptions segment{options.rest_margin_s, options.rest_min_duration_s};
  const RestNoise early = MeasureRestNoise(signal, release.t0_s - kReleaseRoundOffS, segment);
  const RestNoise late = MeasureRestNoise(signal, release.t0_s + kReleaseRoundOffS, segment);
  // Without a rest segment the default estimate is the one used: it is made in full.
  if (!early.available || !late.available) return std::nullopt;
  if (early.samples != late.samples) return std::nullopt;
  if (RestDurationText(early.duration_s) != RestDurationText(late.duration_s)) return std::nullopt;
  return MeasureRestNoise(signal, release.t0_s, segment);
}

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
  // The gyro bias at rest before the release, then the estimate on the corrected signal. The rest segment needs t0
  // alone: from the cheap closed-form fit where that provably places the default fit's segment, else from the full
  // estimate (the one used when there is no rest segment).
  std::optional<RestNoise> rest;
  if (options.subtract_rest_bias) rest = RestBeforeClosedFormRelease(signal, block, parameters, options);
  InitialGuess guess;
  if (!rest) {
    guess = EstimateInitialGuess(signal, block, parameters, options.guess);
    if (options.subtract_rest_bias) {
      rest = MeasureRestNoise(signal, guess.parameters.value(ParameterId::kT0),
                              {options.rest_margin_s, options.rest_min_duration_s});
    }
  }
  Eigen::Vector3d bias = Eigen::Vector3d::Zero();
  bool subtracted = false;
  if (rest && rest->available) {
    bias = rest->mean_rad_s;
    for (Eigen::Vector3d& w : signal.w_B) w -= bias;
    subtracted = true;
    guess = EstimateInitialGuess(signal, block, parameters, options.guess);
    notes.push_back(fmt::format("gyro bias at rest over {} s before the release: ({:.4f}, {:.4f}, {:.4f}) rad/s, "
                                "subtracted{}",
                                RestDurationText(rest->duration_s), bias.x(), bias.y(), bias.z(),
                                rest->cut_before_release_s > 0.0
                                    ? fmt::format(" (the rest ends {:.3f} s earlier than {:.2f} s before the estimated "
                                                  "release: the recording already moves there)",
                                                  rest->cut_before_release_s, options.rest_margin_s)
                                    : std::string()));
  } else if (options.subtract_rest_bias) {
    notes.push_back("gyro bias not measured: the recording starts too close to the release");
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
