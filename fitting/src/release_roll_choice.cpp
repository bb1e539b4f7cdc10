#include "rockfit/fitting/release_roll_choice.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/rest_noise.hpp"

namespace rockfit::fitting {

const char* ToString(ReleaseRollMode mode) {
  switch (mode) {
    case ReleaseRollMode::kOff: return "off";
    case ReleaseRollMode::kAuto: return "auto";
    case ReleaseRollMode::kOn: return "on";
  }
  return "?";
}

bool FromString(std::string_view text, ReleaseRollMode* value) {
  for (ReleaseRollMode m : {ReleaseRollMode::kOff, ReleaseRollMode::kAuto, ReleaseRollMode::kOn}) {
    if (text == ToString(m)) {
      *value = m;
      return true;
    }
  }
  return false;
}

ReleaseRollMode ParseReleaseRollMode(const std::string& name) {
  ReleaseRollMode mode = ReleaseRollMode::kAuto;
  if (!FromString(name, &mode)) {
    throw InvalidArgument(fmt::format("release roll '{}': expected off, auto or on", name));
  }
  return mode;
}

void ReleaseRollChoiceOptions::Validate() const {
  for (double v : {min_roll_to_noise, min_rate_to_noise, rest_margin_s, rest_min_duration_s}) {
    if (!(std::isfinite(v) && v >= 0.0)) {
      throw InvalidArgument(fmt::format("release roll choice options must be finite and non-negative, got {}", v));
    }
  }
}

namespace {

// The fall's samples [first, last): after the rest segment, before the first impact's sample; excluded (clipped)
// samples are skipped by the sums.
struct FallSamples {
  std::size_t first = 0, last = 0;
};

FallSamples FindFall(const MeasuredSignal& signal, double rest_end_s, double t_first_impact_s) {
  FallSamples f;
  while (f.first < signal.size() && signal.t_s[f.first] < rest_end_s) ++f.first;
  f.last = f.first;
  while (f.last < signal.size() && signal.t_s[f.last] < t_first_impact_s) ++f.last;
  return f;
}

std::string Describe(const ReleaseRollChoice& c) {
  if (!c.judged) {
    return c.fitted ? "fitted as asked, started at 0: no rest segment or fall to measure a roll in"
                    : "not fitted: no rest segment or fall to judge a roll against the noise";
  }
  const std::string seen = fmt::format("a roll of {:.3g} mrad seen in the fall, {:.1f} × its noise ({:.2g} mrad)",
                                       1e3 * c.roll_seen_rad, c.roll_noise_rad > 0.0 ? c.roll_seen_rad / c.roll_noise_rad : 0.0,
                                       1e3 * c.roll_noise_rad);
  if (c.mode == ReleaseRollMode::kOn) return fmt::format("fitted as asked; {}; start {:.3g} mrad", seen, 1e3 * c.start_rad);
  return c.fitted ? fmt::format("fitted: {}; start {:.3g} mrad", seen, 1e3 * c.start_rad)
                  : fmt::format("not fitted: {} (the fall is planar)", seen);
}

}  // namespace

ReleaseRollChoice ChooseReleaseRoll(const MeasuredSignal& signal, double t_release_s, double t_first_impact_s,
                                    const ReleaseRollChoiceOptions& options) {
  options.Validate();
  ReleaseRollChoice c;
  c.mode = options.mode;
  c.fitted = options.mode == ReleaseRollMode::kOn;
  if (options.mode == ReleaseRollMode::kOff) {
    c.reason = "not fitted: held at its given value (release roll off)";
    return c;
  }
  const RestNoise rest = MeasureRestNoise(signal, t_release_s, {options.rest_margin_s, options.rest_min_duration_s});
  const double rest_end_s = t_release_s - options.rest_margin_s;
  const FallSamples fall = FindFall(signal, rest_end_s, t_first_impact_s);
  if (!rest.available || fall.last < fall.first + 2 || !(rest.variance_rad2_s2.x() > 0.0)) {
    c.reason = Describe(c);
    return c;
  }
  const double sigma_x = std::sqrt(rest.variance_rad2_s2.x());
  // The rates about their means at rest (a bias not yet removed would add a ramp to the running sum).
  auto wx = [&](std::size_t k) { return signal.w_B[k].x() - rest.mean_rad_s.x(); };
  auto wy = [&](std::size_t k) { return signal.w_B[k].y() - rest.mean_rad_s.y(); };
  // The cross-axis leak s of ω_y into ω_x over the fall (least squares).
  double xy = 0.0, yy = 0.0, y_sum = 0.0;
  for (std::size_t k = fall.first; k < fall.last; ++k) {
    if (signal.is_excluded(k)) continue;
    xy += wx(k) * wy(k);
    yy += wy(k) * wy(k);
    y_sum += wy(k);
  }
  const double s = yy > 0.0 ? xy / yy : 0.0;
  const double dt = (signal.t_s.back() - signal.t_s.front()) / static_cast<double>(signal.size() - 1);
  // The running sum of ω'_x, its largest magnitude, its noise (weights c_k with the regression in them) and the
  // sum at the first landing of the other corner (the first clear peak of |ω'_x|).
  double running = 0.0, largest = 0.0, c_sq = 0.0;
  double at_landing = 0.0;
  bool landed = false;
  double previous_rate = 0.0;
  double previous_running = 0.0;
  for (std::size_t k = fall.first; k < fall.last; ++k) {
    if (signal.is_excluded(k)) continue;
    const double rate = wx(k) - s * wy(k);
    running += dt * rate;
    largest = std::max(largest, std::abs(running));
    const double weight = yy > 0.0 ? 1.0 - wy(k) * y_sum / yy : 1.0;
    c_sq += weight * weight;
    // A peak: the previous sample stood out of the noise and |ω'_x| falls now.
    if (!landed && std::abs(previous_rate) >= options.min_rate_to_noise * sigma_x && std::abs(rate) < std::abs(previous_rate)) {
      at_landing = previous_running;
      landed = true;
    }
    previous_rate = rate;
    previous_running = running;
  }
  if (!landed) at_landing = previous_running;
  c.judged = true;
  c.leak = s;
  c.fall_start_s = signal.t_s[fall.first];
  c.fall_end_s = signal.t_s[fall.last - 1];
  c.roll_seen_rad = largest;
  c.roll_noise_rad = sigma_x * dt * std::sqrt(c_sq);
  c.fitted = options.mode == ReleaseRollMode::kOn || largest >= options.min_roll_to_noise * c.roll_noise_rad;
  // β(t) = β − ∫ω_x dt reaches 0 at the landing: β ≈ the running sum there, with the opposite sign.
  if (c.fitted) c.start_rad = -at_landing;
  c.reason = Describe(c);
  return c;
}

std::string ReleaseRollChoiceJson(const ReleaseRollChoice& c) {
  nlohmann::json j;
  j["mode"] = ToString(c.mode);
  j["judged"] = c.judged;
  j["fitted"] = c.fitted;
  j["roll_seen_rad"] = c.judged ? nlohmann::json(c.roll_seen_rad) : nlohmann::json(nullptr);
  j["roll_noise_rad"] = c.judged ? nlohmann::json(c.roll_noise_rad) : nlohmann::json(nullptr);
  j["leak"] = c.judged ? nlohmann::json(c.leak) : nlohmann::json(nullptr);
  j["start_rad"] = c.fitted ? nlohmann::json(c.start_rad) : nlohmann::json(nullptr);
  j["reason"] = c.reason;
  return j.dump();
}

std::string ReleaseRollChoiceText(const ReleaseRollChoice& c) { return fmt::format("({}) {}", ToString(c.mode), c.reason); }

}  // namespace rockfit::fitting
