#include "rockfit/fitting/data_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include <Eigen/QR>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/core/facet_impact.hpp"
#include "rockfit/core/planar_avrf.hpp"
#include "rockfit/core/planar_rocking.hpp"
#include "rockfit/io/recording.hpp"

namespace rockfit::fitting {
namespace {

// The first facet impact is the first |ω_y| peak reaching this fraction of the recording's largest |ω_y|
// (it has the largest rate of the trial; earlier peaks are noise or handling before the release).
constexpr double kFirstImpactFraction = 0.5;
// λ_lat is matched on this many equally spaced values over its bounds.
constexpr int kLambdaLatScanPoints = 241;
// The impact ending phase 4 has |ω_y| of the order of the first rebound r·ω⁻ (r ≥ 0.79 for λ_lon ≤ 2.5 and
// the paper's blocks); peaks below this fraction of ω⁻ are ringing or lateral edge impacts.
constexpr double kPhaseFourFraction = 0.3;

// Least-squares line through (t_k, y_k), evaluated at t.
double LineAt(const std::vector<double>& t, const std::vector<double>& y, double at) {
  const double n = static_cast<double>(t.size());
  double st = 0, sy = 0, stt = 0, sty = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    st += t[k];
    sy += y[k];
    stt += t[k] * t[k];
    sty += t[k] * y[k];
  }
  const double det = n * stt - st * st;
  if (t.size() < 2 || det <= 0.0) return sy / std::max(n, 1.0);
  const double slope = (n * sty - st * sy) / det;
  return (sy - slope * st) / n + slope * at;
}

// Straight line through samples [first, last] of component c of ω, at time `at`.
double SideValue(const MeasuredSignal& s, std::size_t first, std::size_t last, int c, double at) {
  std::vector<double> t, y;
  for (std::size_t k = first; k <= last && k < s.size(); ++k) {
    t.push_back(s.t_s[k]);
    y.push_back(s.w_B[k][c]);
  }
  return LineAt(t, y, at);
}

// Least-squares parabola through samples [first, last] of component c, at time `at`. Over a few periods of
// the ringing after an impact the oscillation averages out, while the parabola follows the decelerating rate.
double ParabolaValue(const MeasuredSignal& s, std::size_t first, std::size_t last, int c, double at) {
  last = std::min(last, s.size() - 1);
  if (last < first + 3) return SideValue(s, first, last, c, at);
  const std::size_t n = last - first + 1;
  Eigen::MatrixXd a(static_cast<Eigen::Index>(n), 3);
  Eigen::VectorXd y(static_cast<Eigen::Index>(n));
  for (std::size_t k = 0; k < n; ++k) {
    const double dt = s.t_s[first + k] - at;
    a.row(static_cast<Eigen::Index>(k)) << 1.0, dt, dt * dt;
    y[static_cast<Eigen::Index>(k)] = s.w_B[first + k][c];
  }
  return a.colPivHouseholderQr().solve(y)[0];
}

double Clamp(const Parameter& p, double value) { return std::clamp(value, p.lower, p.upper); }

std::vector<io::Peak> Peaks(const MeasuredSignal& s, int axis, const io::ImpactDetectionOptions& options) {
  io::Recording r;
  r.t_s = s.t_s;
  r.w_B = s.w_B;
  r.rate_hz = static_cast<double>(s.size() - 1) / (s.t_s.back() - s.t_s.front());
  return io::DetectRatePeaks(r, axis, options);
}

struct PhaseOne {
  std::size_t peak = 0;      // sample index of the |ω_y| peak before t1
  double t_peak = 0.0;
  double dt = 0.0;           // sample interval after the peak
  double line_at_peak = 0.0; // straight line through the samples before the impact: value at t_peak …
  double line_slope = 0.0;   // … and slope [rad/s²]
  std::size_t post_first = 0, post_last = 0;  // samples of the parabola after the impact
  double t_impact = 0.0;     // the impact time, inside (t_peak, t_peak + dt]
  double w_minus = 0.0;      // ω_y just before, ω just after t_impact
  Eigen::Vector3d w_plus = Eigen::Vector3d::Zero();
  std::vector<io::Peak> peaks;
  std::size_t first = 0;     // index of t1 in peaks

  double LineAt(double t) const { return line_at_peak + line_slope * (t - t_peak); }
  // Moves the impact to t and re-evaluates both sides there.
  void SetImpactTime(const MeasuredSignal& s, double t) {
    t_impact = t;
    w_minus = LineAt(t);
    for (int c = 0; c < 3; ++c) w_plus[c] = ParabolaValue(s, post_first, post_last, c, t);
  }
};

PhaseOne DetectPhaseOne(const MeasuredSignal& s, const EstimateOptions& options) {
  PhaseOne p;
  p.peaks = Peaks(s, 1, options.impacts);
  if (p.peaks.empty()) {
    throw BadInput("no impact found in the recording: |ω_y| has no peak with prominence ≥ " +
                   fmt::format("{} rad/s; check the mounting (ω must be in block axes) or lower it with "
                               "--impact-prominence",
                               options.impacts.min_prominence_rad_s));
  }
  double largest = 0.0;
  for (const io::Peak& q : p.peaks) largest = std::max(largest, q.value);
  for (std::size_t i = 0; i < p.peaks.size(); ++i) {
    if (p.peaks[i].value >= kFirstImpactFraction * largest) {
      p.first = i;
      break;
    }
  }
  p.peak = p.peaks[p.first].index;
  p.t_peak = s.t_s[p.peak];
  p.dt = s.t_s[std::min(p.peak + 1, s.size() - 1)] - p.t_peak;
  const auto side = static_cast<std::size_t>(options.side_samples);
  const std::size_t before = p.peak + 1 >= side ? p.peak + 1 - side : 0;
  p.line_at_peak = SideValue(s, before, p.peak, 1, p.t_peak);
  p.line_slope = p.dt > 0.0 ? SideValue(s, before, p.peak, 1, p.t_peak + p.dt) - p.line_at_peak : 0.0;
  p.line_slope = p.dt > 0.0 ? p.line_slope / p.dt : 0.0;
  p.post_first = p.peak + 1;
  p.post_last = p.peak + static_cast<std::size_t>(options.post_impact_samples);
  p.SetImpactTime(s, p.t_peak + 0.5 * p.dt);  // refined by the energy of phase 1 (EstimateFromData)
  return p;
}

}  // namespace

void EstimateOptions::Validate() const {
  impacts.Validate();
  if (t_end_impact < 0) throw InvalidArgument(fmt::format("t_end_impact must be 0 (phase 4) or a positive count, got {}", t_end_impact));
  if (side_samples < 2) throw InvalidArgument(fmt::format("side_samples must be at least 2, got {}", side_samples));
  if (post_impact_samples < 4) {
    throw InvalidArgument(fmt::format("post_impact_samples must be at least 4, got {}", post_impact_samples));
  }
  if (!(t_end_margin_s >= 0.0 && std::isfinite(t_end_margin_s))) {
    throw InvalidArgument(fmt::format("t_end_margin_s must be a non-negative number of seconds, got {}", t_end_margin_s));
  }
  for (double v : {rest_margin_s, rest_min_duration_s, t0_halfwidth_s}) {
    if (!(std::isfinite(v) && v > 0.0)) throw InvalidArgument("estimate options: durations must be positive");
  }
}

DataEstimate EstimateFromData(const core::Block& block, const MeasuredSignal& measured, const ParameterSet& parameters,
                              const EstimateOptions& options) {
  options.Validate();
  measured.Validate();
  DataEstimate est;
  est.parameters = parameters;
  ParameterSet& p = est.parameters;
  const core::PlanarRocker rocker = core::PlanarRockerAboutEdge(block, 1, 2);
  const double theta_c = rocker.critical_angle_rad;

  // α = ∫ω_y dt over phase 1 (from `from_s` to the impact), t0 = t1 − T(α). The impact lies somewhere in the
  // sample interval after the peak; energy conservation in phase 1 places it: the rate on the line before the
  // impact must reach the landing rate of α, ω⁻ = √(K[cos(θ_c − α) − cos θ_c]). A few fixed-point steps
  // (the tail of the integral depends weakly on the impact time) settle both.
  auto estimate_release = [&](const MeasuredSignal& sig, PhaseOne& one, double from_s, double* alpha, double* t0) {
    const Parameter& a = p[ParameterId::kAlpha];
    const double alpha_max = std::min(a.upper, 0.999 * theta_c);
    double swept_to_peak = 0.0;
    for (std::size_t k = 1; k <= one.peak; ++k) {
      if (sig.t_s[k] <= from_s) continue;
      swept_to_peak += 0.5 * (sig.t_s[k] - sig.t_s[k - 1]) * (sig.w_B[k].y() + sig.w_B[k - 1].y());
    }
    constexpr int kFixedPointSteps = 8;
    double tau = one.t_impact;
    for (int step = 0; step < kFixedPointSteps; ++step) {
      const double swept = swept_to_peak + 0.5 * (tau - one.t_peak) * (sig.w_B[one.peak].y() + one.LineAt(tau));
      *alpha = a.fixed ? a.value : std::clamp(swept, a.lower, alpha_max);
      const double landing = core::LandingRate(rocker, std::min(*alpha, alpha_max));
      if (one.line_slope > 0.0) {
        tau = std::clamp(one.t_peak + (landing - one.line_at_peak) / one.line_slope, one.t_peak, one.t_peak + one.dt);
      }
    }
    one.SetImpactTime(sig, tau);
    *t0 = one.t_impact - core::FallTime(rocker, std::min(*alpha, alpha_max));
  };
  auto alpha_from_energy = [&](const PhaseOne& one) {
    return core::AmplitudeFromLandingRate(rocker, std::abs(one.w_minus)).value_or(theta_c);
  };

  // First pass on the raw signal, then the rest bias, then everything again on the corrected signal.
  PhaseOne one = DetectPhaseOne(measured, options);
  double alpha = 0.0, t0 = 0.0;
  estimate_release(measured, one, measured.t_s.front(), &alpha, &t0);
  // A second pass once t0 is known: integrate from the end of the rest only (less noise and bias).
  estimate_release(measured, one, t0 - options.rest_margin_s, &alpha, &t0);
  MeasuredSignal s = measured;
  const double rest_end = t0 - options.rest_margin_s;
  std::size_t rest_samples = 0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < s.size() && s.t_s[k] < rest_end; ++k, ++rest_samples) sum += s.w_B[k];
  if (rest_samples > 0 && rest_end - s.t_s.front() >= options.rest_min_duration_s) {
    est.rest_bias_rad_s = sum / static_cast<double>(rest_samples);
    est.bias_estimated = true;
    for (Eigen::Vector3d& w : s.w_B) w -= est.rest_bias_rad_s;
    est.notes.push_back(fmt::format("gyro bias at rest ({:.3f} s before the release) ({:.4f}, {:.4f}, {:.4f}) rad/s",
                                    rest_end - s.t_s.front(), est.rest_bias_rad_s.x(), est.rest_bias_rad_s.y(),
                                    est.rest_bias_rad_s.z()));
    one = DetectPhaseOne(s, options);
    estimate_release(s, one, rest_end, &alpha, &t0);
    estimate_release(s, one, t0 - options.rest_margin_s, &alpha, &t0);
  } else {
    est.notes.push_back("gyro bias not estimated: the recording starts too close to the release");
  }
  est.alpha_from_energy_rad = alpha_from_energy(one);
  if (one.w_minus <= 0.0) {
    est.warnings.push_back(fmt::format(
        "ω_y = {:.3f} rad/s before the first impact is not positive: a release on V1V2 falls with ω_y > 0 "
        "(DESIGN §2); check the mounting of the sensor",
        one.w_minus));
  }
  est.w_minus_rad_s = one.w_minus;
  est.w_plus_rad_s = one.w_plus;
  est.first_impact_s = one.t_impact;
  for (const io::Peak& q : one.peaks) est.impact_times_s.push_back(s.t_s[q.index]);
  std::optional<std::size_t> end_index;
  if (options.t_end_impact == 0) {
    for (std::size_t i = one.first + 1; i < one.peaks.size(); ++i) {
      const double w_y = s.w_B[one.peaks[i].index].y();
      if (w_y < 0.0 && -w_y >= kPhaseFourFraction * std::abs(one.w_minus)) {
        end_index = i;
        break;
      }
    }
    if (!end_index) {
      throw BadInput(
          "phase 4 does not end in the recording: after the first facet impact no |ω_y| peak has ω_y < 0 (the "
          "block falling back onto its release side); give the end of the window with --t-end SECONDS");
    }
  } else {
    const std::size_t i = one.first + static_cast<std::size_t>(options.t_end_impact) - 1;
    if (i >= one.peaks.size()) {
      throw BadInput(fmt::format(
          "the window should end at base impact #{} after the release, but only {} impact(s) were found from the "
          "first facet impact on; give the end of the window with --t-end SECONDS",
          options.t_end_impact, one.peaks.size() - one.first));
    }
    end_index = i;
  }
  est.t_end_impact_s = s.t_s[one.peaks[*end_index].index];
  est.t_end_s = std::max(est.t_end_impact_s - options.t_end_margin_s, 0.5 * (est.t_end_impact_s + one.t_impact));

  // t0 and α.
  Parameter& t0p = p[ParameterId::kT0];
  if (!t0p.fixed) {
    if (!std::isfinite(t0p.lower)) t0p.lower = std::max(s.t_s.front(), t0 - options.t0_halfwidth_s);
    if (!std::isfinite(t0p.upper)) t0p.upper = std::min(one.t_impact, t0 + options.t0_halfwidth_s);
    t0p.value = Clamp(t0p, t0);
  }
  if (!p[ParameterId::kAlpha].fixed) p[ParameterId::kAlpha].value = Clamp(p[ParameterId::kAlpha], alpha);
  est.notes.push_back(fmt::format(
      "first impact at {:.4f} s with ω_y⁻ = {:.4f} rad/s: α = {:.4f} rad (∫ω_y dt; by energy {:.4f}), t0 = {:.4f} s",
      one.t_impact, one.w_minus, alpha, est.alpha_from_energy_rad, t0));

  // λ_lon from the first jump, (6) inverted.
  const double w_minus = std::max(std::abs(one.w_minus), 1e-9);
  if (!p[ParameterId::kLambdaLon].fixed) {
    const double r = one.w_plus.y() / w_minus;
    const double lambda_lon = core::LambdaFromAvrf(core::PlanarBlockAboutY(block), r);
    p[ParameterId::kLambdaLon].value = Clamp(p[ParameterId::kLambdaLon], std::isfinite(lambda_lon) ? lambda_lon : 1.0);
    est.notes.push_back(fmt::format("first jump r = ω_y⁺/ω_y⁻ = {:.4f}: λ_lon = {:.4f} by (6)", r, lambda_lon));
  }
  // λ_lat by matching ω_x⁺ with the unified facet map.
  if (!p[ParameterId::kLambdaLat].fixed) {
    const Parameter& lat = p[ParameterId::kLambdaLat];
    core::FacetImpactParameters map;
    map.lambda_lon = p.value(ParameterId::kLambdaLon);
    map.tau_rule = p.facet_tau_rule();
    double best = lat.value, best_miss = std::numeric_limits<double>::infinity();
    for (int j = 0; j < kLambdaLatScanPoints; ++j) {
      map.lambda_lat = lat.lower + (lat.upper - lat.lower) * j / (kLambdaLatScanPoints - 1);
      const core::ImpactOutcome out = core::FacetImpact(block, 2, Eigen::Vector3d(0.0, w_minus, 0.0), map);
      if (out.status != core::ImpactStatus::kOk) continue;
      const double miss = std::abs(out.w_plus_B.x() - one.w_plus.x());
      if (miss < best_miss) {
        best_miss = miss;
        best = map.lambda_lat;
      }
    }
    p[ParameterId::kLambdaLat].value = best;
    est.notes.push_back(fmt::format("ω_x⁺ = {:.4f} rad/s after the first impact: λ_lat = {:.3f} by the facet map",
                                    one.w_plus.x(), best));
  }
  // λ from the decay of the lateral rocking.
  if (!p[ParameterId::kLambda].fixed) {
    std::vector<double> values;
    for (const io::Peak& q : Peaks(s, 0, options.impacts)) {
      if (s.t_s[q.index] > one.t_impact && s.t_s[q.index] < est.t_end_s) values.push_back(q.value);
    }
    double r = 0.0;
    if (values.size() >= 2) {
      std::vector<double> ratios;
      for (std::size_t i = 1; i < values.size(); ++i) ratios.push_back(values[i] / values[i - 1]);
      std::nth_element(ratios.begin(), ratios.begin() + static_cast<std::ptrdiff_t>(ratios.size() / 2), ratios.end());
      r = ratios[ratios.size() / 2];
    }
    if (r > 0.0 && r < 1.0) {
      const double lambda = core::LambdaFromAvrf(core::PlanarBlockAboutX(block), r);
      p[ParameterId::kLambda].value = Clamp(p[ParameterId::kLambda], std::isfinite(lambda) ? lambda : 1.0);
      est.notes.push_back(fmt::format("{} lateral peaks, median ratio {:.3f}: λ = {:.3f} by (6) about x",
                                      values.size(), r, lambda));
    } else {
      p[ParameterId::kLambda].value = Clamp(p[ParameterId::kLambda], p.value(ParameterId::kLambda));
      est.notes.push_back(fmt::format(
          "{} lateral peaks in the window (median ratio {:.3f}): no decay to read λ from, it starts at {}",
          values.size(), r, p.value(ParameterId::kLambda)));
    }
  }
  return est;
}

}  // namespace rockfit::fitting
