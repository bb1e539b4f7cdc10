#include "rockfit/io/drift_correction.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/io/euler_kinematics.hpp"

namespace rockfit::io {

const char* ToString(AnchorMethod method) {
  switch (method) {
    case AnchorMethod::kSubsample: return "subsample";
    case AnchorMethod::kSample: return "sample";
  }
  return "unknown";
}

const char* ToString(AnchorSource source) {
  switch (source) {
    case AnchorSource::kOmegaY: return "omega_y";
    case AnchorSource::kOmegaX: return "omega_x";
  }
  return "unknown";
}

void DriftCorrectionOptions::Validate() const {
  impacts.Validate();
  if (!std::isfinite(anchor_fit_half_window_s) || anchor_fit_half_window_s <= 0.0) {
    throw InvalidArgument("anchor_fit_half_window_s must be a positive number of seconds");
  }
  if (!std::isfinite(min_rate_jump_rad_s) || min_rate_jump_rad_s < 0.0) {
    throw InvalidArgument("min_rate_jump_rad_s must be a finite number ≥ 0 [rad/s]");
  }
}

double DriftAt(const std::vector<Anchor>& anchors, double t_s) {
  if (anchors.empty()) return 0.0;
  if (t_s <= anchors.front().t_s) return anchors.front().value_rad;
  if (t_s >= anchors.back().t_s) return anchors.back().value_rad;
  const auto after = std::upper_bound(anchors.begin(), anchors.end(), t_s,
                                      [](double t, const Anchor& a) { return t < a.t_s; });
  const Anchor& a = *(after - 1);
  const Anchor& b = *after;
  const double span = b.t_s - a.t_s;
  if (!(span > 0.0)) return b.value_rad;
  return a.value_rad + (b.value_rad - a.value_rad) * (t_s - a.t_s) / span;
}

namespace {

// Euler angle (component 1 = φy, 2 = φx) and its rate from the gyro through the ZYX kinematics.
struct AngleAndRate {
  std::vector<double> angle_rad;
  std::vector<double> rate_rad_s;
};

AngleAndRate ExtractAngle(const Recording& recording, int component) {
  AngleAndRate out;
  out.angle_rad.resize(recording.size());
  out.rate_rad_s.resize(recording.size());
  for (std::size_t i = 0; i < recording.size(); ++i) {
    out.angle_rad[i] = recording.euler_zyx[i][component];
    out.rate_rad_s[i] = EulerZyxRates(recording.euler_zyx[i], recording.w_B[i])[component];
  }
  return out;
}

Anchor MakeAnchor(const Recording& recording, const AngleAndRate& signal, const Peak& peak, AnchorSource source,
                  const DriftCorrectionOptions& options, const AnchorFitOptions& fit_options,
                  std::optional<double> known_t_s = std::nullopt) {
  Anchor anchor;
  anchor.index = peak.index;
  anchor.source = source;
  anchor.peak_rad_s = peak.value;
  if (options.anchor_method == AnchorMethod::kSample) {
    anchor.t_s = recording.t_s[peak.index];
    anchor.value_rad = signal.angle_rad[peak.index];
    return anchor;
  }
  const AnchorEstimate estimate =
      EstimateAnchor(recording.t_s, signal.angle_rad, signal.rate_rad_s, peak.index, fit_options, known_t_s);
  anchor.t_s = estimate.t_s;
  anchor.value_rad = estimate.value_rad;
  return anchor;
}

void RequireUsable(const Recording& recording) {
  if (!recording.has_euler()) {
    throw BadInput("recording '" + recording.source +
                   "' has no Euler angles; drift correction needs them (export EulerAngles, Quaternion or "
                   "RotationMatrix from the IMU)");
  }
  if (recording.euler_zyx.size() != recording.size() || recording.w_B.size() != recording.size()) {
    throw BadInput("recording '" + recording.source + "': time, angular velocity and Euler angles differ in length");
  }
  for (std::size_t i = 0; i < recording.size(); ++i) {
    if (!recording.euler_zyx[i].allFinite() || !std::isfinite(recording.t_s[i])) {
      throw BadInput("recording '" + recording.source + "': sample " + std::to_string(i) +
                     " has a time or Euler angle that is not a finite number");
    }
  }
}

}  // namespace

DriftCorrection CorrectDrift(const Recording& recording, const DriftCorrectionOptions& options) {
  options.Validate();
  RequireUsable(recording);
  DriftCorrection result;
  result.euler_raw_zyx = recording.euler_zyx;
  result.euler_corrected_zyx = recording.euler_zyx;

  AnchorFitOptions fit_options;
  fit_options.half_window_samples = std::max<std::size_t>(
      3, static_cast<std::size_t>(std::lround(options.anchor_fit_half_window_s * recording.rate_hz)));
  fit_options.min_rate_jump_rad_s = options.min_rate_jump_rad_s;

  const AngleAndRate phi_y = ExtractAngle(recording, 1);
  const AngleAndRate phi_x = ExtractAngle(recording, 2);

  for (const Peak& peak : DetectRatePeaks(recording, 1, options.impacts)) {
    result.impacts_y.push_back(MakeAnchor(recording, phi_y, peak, AnchorSource::kOmegaY, options, fit_options));
  }
  std::stable_sort(result.impacts_y.begin(), result.impacts_y.end(),
                   [](const Anchor& a, const Anchor& b) { return a.t_s < b.t_s; });
  if (result.impacts_y.empty()) {
    result.warnings.push_back(fmt::format(
        "no impact found: no peak of |ω_y| with prominence ≥ {:g} rad/s; the angles are left uncorrected",
        options.impacts.min_prominence_rad_s));
    return result;
  }

  // φ_x: at the |ω_x| peaks and at the |ω_y| impacts. An |ω_x| peak within the minimum separation of an |ω_y|
  // impact is the same impact seen on both axes: it takes the impact time found from φ_y, which the larger
  // in-plane rate jump locates better. The other |ω_x| peaks (edge impacts) are located on φ_x itself.
  const std::vector<Peak> x_peaks = DetectRatePeaks(recording, 0, options.impacts);
  const std::size_t separation_samples =
      std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(options.impacts.min_separation_s * recording.rate_hz)));
  const auto near = [&](std::size_t a, std::size_t b) { return (a > b ? a - b : b - a) < separation_samples; };
  const bool subsample = options.anchor_method == AnchorMethod::kSubsample;
  std::vector<bool> impact_used(result.impacts_y.size(), false);
  for (const Peak& peak : x_peaks) {
    std::optional<std::size_t> same;
    for (std::size_t i = 0; i < result.impacts_y.size(); ++i) {
      if (near(peak.index, result.impacts_y[i].index) && !impact_used[i]) {
        same = i;
        break;
      }
    }
    std::optional<double> known_t;
    if (same) {
      impact_used[*same] = true;
      if (subsample) known_t = result.impacts_y[*same].t_s;
    }
    result.anchors_x.push_back(
        MakeAnchor(recording, phi_x, peak, AnchorSource::kOmegaX, options, fit_options, known_t));
  }
  result.omega_x_peaks = result.anchors_x.size();
  for (std::size_t i = 0; i < result.impacts_y.size(); ++i) {
    if (impact_used[i]) continue;
    const Anchor& impact = result.impacts_y[i];
    const bool covered = std::any_of(x_peaks.begin(), x_peaks.end(), [&](const Peak& p) { return near(p.index, impact.index); });
    if (covered) continue;
    Peak at_impact{impact.index, impact.peak_rad_s, 0.0};
    result.anchors_x.push_back(MakeAnchor(recording, phi_x, at_impact, AnchorSource::kOmegaY, options, fit_options,
                                          subsample ? std::optional<double>(impact.t_s) : std::nullopt));
  }
  std::sort(result.anchors_x.begin(), result.anchors_x.end(),
            [](const Anchor& a, const Anchor& b) { return a.t_s < b.t_s; });

  for (std::size_t i = 0; i < recording.size(); ++i) {
    const double t = recording.t_s[i];
    result.euler_corrected_zyx[i][1] -= DriftAt(result.impacts_y, t);
    result.euler_corrected_zyx[i][2] -= DriftAt(result.anchors_x, t);
  }
  return result;
}

}  // namespace rockfit::io
