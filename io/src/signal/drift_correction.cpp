#include "rockfit/io/drift_correction.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "signal/euler_kinematics.hpp"
#include "rockfit/io/gyro_attitude.hpp"
#include "rockfit/io/impact_consistency.hpp"
#include "rockfit/core/enum_names.hpp"

namespace rockfit::io {

const char* ToString(AnchorMethod method) {
  switch (method) {
    case AnchorMethod::kSubsample: return "subsample";
    case AnchorMethod::kSample: return "sample";
  }
  return "unknown";
}

bool FromString(std::string_view text, AnchorMethod* method) {
  for (AnchorMethod m : {AnchorMethod::kSubsample, AnchorMethod::kSample}) {
    if (text == ToString(m)) {
      *method = m;
      return true;
    }
  }
  return false;
}

const char* ToString(AnchorSource source) {
  switch (source) {
    case AnchorSource::kOmegaY: return "omega_y";
    case AnchorSource::kOmegaX: return "omega_x";
  }
  return "unknown";
}

bool FromString(std::string_view text, AnchorSource* value) {
  static constexpr AnchorSource kAll[] = {AnchorSource::kOmegaY, AnchorSource::kOmegaX};
  return core::FromStringAmong(text, kAll, value);
}

void DriftCorrectionOptions::Validate() const {
  impacts.Validate();
  consistency.Validate();
  if (!std::isfinite(anchor_fit_half_window_s) || anchor_fit_half_window_s <= 0.0) {
    throw InvalidArgument("anchor_fit_half_window_s must be a positive number of seconds");
  }
  if (!std::isfinite(min_rate_jump_rad_s) || min_rate_jump_rad_s < 0.0) {
    throw InvalidArgument("min_rate_jump_rad_s must be a finite number ≥ 0 [rad/s]");
  }
  zero_crossing.Validate();
  if (gyro_impact_passes < 0) throw InvalidArgument("gyro_impact_passes must be ≥ 0");
  if (!std::isfinite(same_impact_s) || same_impact_s < 0.0 || same_impact_s >= impacts.min_separation_s) {
    throw InvalidArgument("same_impact_s must be ≥ 0 and shorter than the impacts' min_separation_s [s]");
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

// The candidates at which the angle is zero (impact_consistency.hpp); all of them when the check is off.
std::vector<Anchor> KeepZeroInstants(const Recording& recording, const AngleAndRate& signal,
                                     const std::vector<Anchor>& candidates, const DriftCorrectionOptions& options,
                                     std::size_t* rejected) {
  *rejected = 0;
  if (!options.check_zero_instants) return candidates;
  std::vector<double> times, strength;
  for (const Anchor& a : candidates) {
    times.push_back(a.t_s);
    strength.push_back(a.peak_rad_s);
  }
  std::vector<Anchor> kept;
  for (std::size_t j : ConsistentZeroInstants(recording.t_s, signal.rate_rad_s, times, strength, options.consistency)) {
    kept.push_back(candidates[j]);
  }
  *rejected = candidates.size() - kept.size();
  return kept;
}

// The impact times at which the next integration of a gyro-only attitude splits its sample intervals: each anchor
// of φ_y, and each anchor of φ_x marked by its own |ω_x| peak, moved to where its angle minus the error Ê read
// from all of its axis' anchors crosses zero (impact_zero_crossing.hpp); an anchor without such a crossing in its
// interval keeps its time. One time per sample interval (φ_y's first), increasing.
std::vector<double> ImpactTimesAtZero(const Recording& integrated, const DriftCorrection& correction,
                                      const ZeroCrossingOptions& options) {
  const std::vector<double>& t = integrated.t_s;
  std::vector<std::pair<std::size_t, double>> located;  // (interval, time)
  const auto locate = [&](const std::vector<Anchor>& anchors, int component, bool only_own_peaks) {
    const AngleAndRate signal = ExtractAngle(integrated, component);
    struct Candidate {
      std::size_t interval;
      double t_s;
      bool moved;  // located here (φ_x's anchors at φ_y's impacts only read the error)
      std::optional<BeforeImpact> before;
    };
    std::vector<Candidate> candidates;
    std::vector<DriftPoint> readings;
    for (const Anchor& a : anchors) {
      const auto after = std::upper_bound(t.begin(), t.end(), a.t_s);
      if (after == t.begin() || after == t.end()) continue;
      const auto m = static_cast<std::size_t>(after - t.begin()) - 1;
      Candidate c{m, a.t_s, !only_own_peaks || a.source == AnchorSource::kOmegaX,
                  AngleBeforeImpact(t, signal.angle_rad, signal.rate_rad_s, m, options)};
      if (c.before) readings.push_back(c.before->MiddleReading(options.reading_scatter_rad));
      candidates.push_back(c);
    }
    for (const Candidate& c : candidates) {
      if (!c.moved) continue;
      std::optional<double> tau;
      if (c.before) tau = ZeroCrossingTime(*c.before, SmoothDriftAt(readings, c.before->t0_s, options.drift_half_window_s));
      located.emplace_back(c.interval, tau.value_or(c.t_s));
    }
  };
  locate(correction.impacts_y, 1, false);
  locate(correction.anchors_x, 2, true);
  std::stable_sort(located.begin(), located.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<double> times;
  for (std::size_t i = 0; i < located.size(); ++i) {
    if (i > 0 && located[i].first == located[i - 1].first) continue;
    times.push_back(located[i].second);
  }
  return times;
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

// The correction of a recording's own Euler angles (file or integrated).
DriftCorrection CorrectAngles(const Recording& recording, const DriftCorrectionOptions& options) {
  RequireUsable(recording);
  DriftCorrection result;
  result.attitude = "file";
  result.euler_raw_zyx = recording.euler_zyx;
  result.euler_corrected_zyx = recording.euler_zyx;

  AnchorFitOptions fit_options;
  fit_options.half_window_samples = std::max<std::size_t>(
      3, static_cast<std::size_t>(std::lround(options.anchor_fit_half_window_s * recording.rate_hz)));
  fit_options.min_rate_jump_rad_s = options.min_rate_jump_rad_s;

  const AngleAndRate phi_y = ExtractAngle(recording, 1);
  const AngleAndRate phi_x = ExtractAngle(recording, 2);

  // φ_y: the peaks of |ω_y|, located inside their sample interval, then only those where φ_y is zero.
  std::vector<Anchor> candidates_y;
  for (const Peak& peak : DetectRatePeaks(recording, 1, options.impacts)) {
    candidates_y.push_back(MakeAnchor(recording, phi_y, peak, AnchorSource::kOmegaY, options, fit_options));
  }
  std::stable_sort(candidates_y.begin(), candidates_y.end(),
                   [](const Anchor& a, const Anchor& b) { return a.t_s < b.t_s; });
  result.impacts_y = KeepZeroInstants(recording, phi_y, candidates_y, options, &result.rejected_y);
  if (result.rejected_y > 0) {
    result.warnings.push_back(fmt::format(
        "{} peak(s) of |ω_y| were not taken as impacts: the pitch integrated from the gyro does not come back to "
        "zero there (a tilted block rolling onto a neighbouring vertex)",
        result.rejected_y));
  }
  if (result.impacts_y.empty()) {
    result.warnings.push_back(fmt::format(
        "no impact found: no peak of |ω_y| with prominence ≥ {:g} rad/s; the angles are left uncorrected",
        options.impacts.min_prominence_rad_s));
    return result;
  }

  // φ_x: at the peaks of |ω_x| (landings on a base edge along y or on the whole base: φ_x = 0). A peak within
  // `same_impact_s` of an impact of φ_y is a landing on the whole base seen on both axes (ringing can delay the
  // peak of the smaller rate by a sample or two): it takes that impact's time, which the larger in-plane rate
  // jump locates better. Where ω_x has no significant peak between two impacts
  // of φ_y (planar rocking), those impacts anchor φ_x too.
  const std::vector<Peak> x_peaks = DetectRatePeaks(recording, 0, options.impacts);
  const bool subsample = options.anchor_method == AnchorMethod::kSubsample;
  const auto distance = [](std::size_t a, std::size_t b) { return a > b ? a - b : b - a; };
  const auto same_impact_samples = static_cast<std::size_t>(std::lround(options.same_impact_s * recording.rate_hz));
  std::vector<Anchor> candidates_x;
  for (const Peak& peak : x_peaks) {
    std::optional<double> known_t;
    for (const Anchor& impact : result.impacts_y) {
      if (distance(peak.index, impact.index) <= same_impact_samples && subsample) known_t = impact.t_s;
    }
    candidates_x.push_back(MakeAnchor(recording, phi_x, peak, AnchorSource::kOmegaX, options, fit_options, known_t));
  }
  for (std::size_t i = 0; i < result.impacts_y.size(); ++i) {
    const Anchor& impact = result.impacts_y[i];
    const std::size_t from = i > 0 ? result.impacts_y[i - 1].index : 0;
    const std::size_t to = i + 1 < result.impacts_y.size() ? result.impacts_y[i + 1].index : recording.size();
    const bool planar = std::none_of(x_peaks.begin(), x_peaks.end(), [&](const Peak& p) {
      return p.index > from && p.index < to;
    });
    if (!planar) continue;
    Peak at_impact{impact.index, impact.peak_rad_s, 0.0};
    candidates_x.push_back(MakeAnchor(recording, phi_x, at_impact, AnchorSource::kOmegaY, options, fit_options,
                                      subsample ? std::optional<double>(impact.t_s) : std::nullopt));
  }
  std::stable_sort(candidates_x.begin(), candidates_x.end(),
                   [](const Anchor& a, const Anchor& b) { return a.t_s < b.t_s; });
  result.anchors_x = KeepZeroInstants(recording, phi_x, candidates_x, options, &result.rejected_x);
  result.omega_x_peaks = static_cast<std::size_t>(std::count_if(
      result.anchors_x.begin(), result.anchors_x.end(), [](const Anchor& a) { return a.source == AnchorSource::kOmegaX; }));

  for (std::size_t i = 0; i < recording.size(); ++i) {
    const double t = recording.t_s[i];
    result.euler_corrected_zyx[i][1] -= DriftAt(result.impacts_y, t);
    result.euler_corrected_zyx[i][2] -= DriftAt(result.anchors_x, t);
  }
  return result;
}

}  // namespace

DriftCorrection CorrectDrift(const Recording& recording, const DriftCorrectionOptions& options) {
  options.Validate();
  if (!recording.has_euler() && recording.size() > 0) {
    // No attitude in the files: integrate it from the gyro (gyro_attitude.hpp).
    GyroAttitudeOptions attitude_options;
    Recording integrated = WithAttitude(recording, attitude_options);
    DriftCorrection result = CorrectAngles(integrated, options);
    // The anchors of the angle integrated by the mean rule sit near their intervals' middles; each pass moves them
    // to where the levelled angle comes back to zero and integrates again with the rate jumps placed there.
    for (int pass = 0; pass < options.gyro_impact_passes; ++pass) {
      attitude_options.impact_times_s = ImpactTimesAtZero(integrated, result, options.zero_crossing);
      if (attitude_options.impact_times_s.empty()) break;
      integrated = WithAttitude(recording, attitude_options);
      result = CorrectAngles(integrated, options);
    }
    result.attitude = integrated.orientation_source;
    std::vector<std::string> notes{"the recording has no attitude; it was " + integrated.orientation_source};
    notes.insert(notes.end(), integrated.warnings.begin() + static_cast<std::ptrdiff_t>(recording.warnings.size()),
                 integrated.warnings.end());
    result.warnings.insert(result.warnings.begin(), notes.begin(), notes.end());
    return result;
  }
  return CorrectAngles(recording, options);
}

}  // namespace rockfit::io
