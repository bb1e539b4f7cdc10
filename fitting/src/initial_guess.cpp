#include "rockfit/fitting/initial_guess.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/core/facet_impact.hpp"
#include "rockfit/core/planar_avrf.hpp"
#include "rockfit/core/planar_rocking.hpp"
#include "rockfit/fitting/initial_guess_fall.hpp"
#include "rockfit/io/peak_finding.hpp"
#include "upper_median.hpp"

namespace rockfit::fitting {
namespace {

// A base impact on the release side can be recognised by the tilt about y passing through zero within this many
// samples of an |ω_y| peak: one because the peak sample may be on either side of the impact, one more for the
// drift of the integrated attitude (a gyro bias of 0.3 °/s tilts it by 2 mrad in 0.4 s).
constexpr double kLandingSamples = 2.0;
// The planar fit searches α within this distance of the landing-rate estimate and of the swept angle [rad]:
// the landing rate read from one sample before the impact is low by at most one sample of angular
// acceleration (≈ 5 % in α away from the critical angle).
constexpr double kAlphaSearchHalfWidthRad = 0.03;
// Points of the α scan before the golden section (or Brent's method): a step of 2 mrad over the ±0.03 rad interval.
constexpr int kAlphaScanPoints = 30;
// Golden-section iterations: (0.618)^40 of the interval, far below the resolution of the data.
constexpr int kGoldenIterations = 40;
// With InitialGuessOptions::closed_form_fall, Brent's method stops when the minimum is bracketed to within four
// times these: far below the data's resolution (a sample is 3.9 ms at 256 Hz; α moves the landing rate by ~10 rad/s
// per rad), and at the resolution of the cost itself (the model is linear between nodes, so its minimum in t0 is
// defined to ~1e-9 s).
constexpr double kPhase1T0ToleranceS = 1e-11;
constexpr double kPhase1AlphaToleranceRad = 1e-11;
// The phase-1 fit looks at the data from this multiple of T(α) before the impact (it sees the release).
constexpr double kPhase1WindowFactor = 1.5;

template <typename F>
double GoldenMinimum(double lo, double hi, F&& f) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = lo, b = hi;
  double c = b - g * (b - a), d = a + g * (b - a);
  double fc = f(c), fd = f(d);
  for (int i = 0; i < kGoldenIterations; ++i) {
    if (fc < fd) {
      b = d; d = c; fd = fc; c = b - g * (b - a); fc = f(c);
    } else {
      a = c; c = d; fc = fd; d = a + g * (b - a); fd = f(d);
    }
  }
  return 0.5 * (a + b);
}

// The minimum of f on [lo, hi] by Brent's method: golden-section steps, and parabolic steps through the three best
// points when they fall inside the bracket and shrink it fast enough; it stops when the minimum is bracketed to
// within 4·tolerance (at least tolerance between evaluations). A smooth f needs ~10 evaluations where golden
// sections alone need ~40.
template <typename F>
double BrentMinimum(double lo, double hi, double tolerance, F&& f) {
  const double golden = 0.5 * (3.0 - std::sqrt(5.0));  // 0.382: the golden section of the larger part
  double a = lo, b = hi;
  double x = a + golden * (b - a), w = x, v = x;  // the best point, the second best, the previous second best
  double fx = f(x), fw = fx, fv = fx;
  double step = 0.0, previous_step = 0.0;         // the last step and the one before it
  for (;;) {
    const double middle = 0.5 * (a + b);
    if (std::abs(x - middle) <= 2.0 * tolerance - 0.5 * (b - a)) break;
    bool parabolic = false;
    if (std::abs(previous_step) > tolerance) {
      // The vertex of the parabola through (v, fv), (w, fw), (x, fx), as x + p/q.
      const double r = (x - w) * (fx - fv);
      double q = (x - v) * (fx - fw);
      double p = (x - v) * q - (x - w) * r;
      q = 2.0 * (q - r);
      if (q > 0.0) p = -p;
      q = std::abs(q);
      // Taken when it lies inside the bracket and moves less than half the step before last (it converges).
      if (std::abs(p) < std::abs(0.5 * q * previous_step) && p > q * (a - x) && p < q * (b - x)) {
        previous_step = step;
        step = p / q;
        parabolic = true;
        const double u = x + step;
        if (u - a < 2.0 * tolerance || b - u < 2.0 * tolerance) step = middle > x ? tolerance : -tolerance;
      }
    }
    if (!parabolic) {
      previous_step = x >= middle ? a - x : b - x;
      step = golden * previous_step;
    }
    const double u = std::abs(step) >= tolerance ? x + step : x + (step > 0.0 ? tolerance : -tolerance);
    const double fu = f(u);
    if (fu <= fx) {
      (u >= x ? a : b) = x;
      v = w, fv = fw;
      w = x, fw = fx;
      x = u, fx = fu;
    } else {
      (u < x ? a : b) = u;
      if (fu <= fw || w == x) {
        v = w, fv = fw;
        w = u, fw = fu;
      } else if (fu <= fv || v == x || v == w) {
        v = u, fv = fu;
      }
    }
  }
  return x;
}

// Inverse of LandingRate by bisection on [0, θ_c].
double AlphaFromLandingRate(const core::PlanarRocker& rocker, double rate_rad_s) {
  double lo = 0.0, hi = rocker.critical_angle_rad;
  if (core::LandingRate(rocker, hi) <= rate_rad_s) return hi;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (core::LandingRate(rocker, mid) < rate_rad_s ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

std::vector<io::Peak> RatePeaks(const MeasuredSignal& signal, int axis, const io::ImpactDetectionOptions& options) {
  std::vector<double> magnitude(signal.size());
  for (std::size_t k = 0; k < signal.size(); ++k) magnitude[k] = std::abs(signal.w_B[k][axis]);
  const double dt = (signal.t_s.back() - signal.t_s.front()) / static_cast<double>(signal.size() - 1);
  io::PeakOptions peak;
  peak.min_prominence = options.min_prominence_rad_s;
  peak.min_separation_samples = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(options.min_separation_s / dt)));
  return io::FindPeaks(magnitude, peak);
}

// A peak of |ω_y| on a clipped gyro is a flat top at the rail (gyro_clipping.hpp), and FindPeaks puts it at the
// top's middle. The impact lies inside the top or right after its last sample: the block turns fastest just
// before an impact, and after it |ω_y| falls by the restitution, which may leave it above the rail for a while.
struct ClippedTop {
  std::size_t first = 0, last = 0;  // the samples of the top (first == last == the peak when it is not clipped)
  bool clipped = false;
};

ClippedTop ClippedTopAround(const MeasuredSignal& signal, std::size_t k) {
  ClippedTop top{k, k, signal.is_excluded(k)};
  if (!top.clipped) return top;
  const double rail = std::abs(signal.w_B[k][1]);
  auto at_rail = [&](std::size_t i) { return signal.is_excluded(i) && std::abs(signal.w_B[i][1]) == rail; };
  while (top.first > 0 && at_rail(top.first - 1)) --top.first;
  while (top.last + 1 < signal.size() && at_rail(top.last + 1)) ++top.last;
  return top;
}

// |ω_y| falls by at least `fraction` of its value from sample k to the next.
bool DropsAfter(const MeasuredSignal& signal, std::size_t k, double fraction) {
  if (k + 1 >= signal.size()) return false;
  const double w = std::abs(signal.w_B[k][1]);
  return w - std::abs(signal.w_B[k + 1][1]) >= fraction * w;
}

double Clamp(const Parameter& p, double v) { return std::min(std::max(v, p.lower), p.upper); }

void SetValue(ParameterSet* set, ParameterId id, double v) {
  Parameter& p = (*set)[id];
  if (!p.fixed) p.value = Clamp(p, v);
}

}  // namespace

void InitialGuessOptions::Validate() const {
  detection.Validate();
  if (!(first_impact_fraction > 0.0 && first_impact_fraction <= 1.0)) {
    throw InvalidArgument(fmt::format("first_impact_fraction must lie in (0, 1], got {}", first_impact_fraction));
  }
  if (window_end_impact < 2) throw InvalidArgument("window_end_impact must be at least 2 (the second base impact)");
  if (!(later_impact_fraction > 0.0 && later_impact_fraction <= 1.0)) {
    throw InvalidArgument(fmt::format("later_impact_fraction must lie in (0, 1], got {}", later_impact_fraction));
  }
  if (!std::isfinite(default_lambda)) throw InvalidArgument("default_lambda must be finite");
  if (!(min_jump_fraction >= 0.0 && min_jump_fraction < 1.0)) {
    throw InvalidArgument(fmt::format("min_jump_fraction must lie in [0, 1), got {}", min_jump_fraction));
  }
  if (!(flat_tilt_fraction > 0.0 && flat_tilt_fraction < 1.0)) {
    throw InvalidArgument(fmt::format("flat_tilt_fraction must lie in (0, 1), got {}", flat_tilt_fraction));
  }
  if (post_impact_samples < 1) throw InvalidArgument("post_impact_samples must be at least 1");
}

namespace {

// The base impacts of DetectBaseImpactTimes; with `first_only` the first alone (it does not depend on the later
// ones), without the attitude integration that only the later ones need.
std::vector<double> BaseImpactTimes(const MeasuredSignal& signal, const InitialGuessOptions& options, bool first_only) {
  const std::vector<io::Peak> peaks = RatePeaks(signal, 1, options.detection);
  double largest = 0.0;
  for (const io::Peak& p : peaks) largest = std::max(largest, p.value);
  std::vector<double> times;
  double first_value = 0.0, first_sign = 1.0;
  std::vector<double> tilt_y(signal.size(), 0.0), max_tilt_y(signal.size(), 0.0);  // [rad]
  for (const io::Peak& p : peaks) {
    if (times.empty()) {
      if (p.value >= options.first_impact_fraction * largest) {
        // On a clipped top, the impact is at its last sample when |ω_y| drops right after it (else inside it).
        const ClippedTop top = ClippedTopAround(signal, p.index);
        const std::size_t k_impact = top.clipped && DropsAfter(signal, top.last, options.min_jump_fraction) ? top.last
                                                                                                              : p.index;
        times.push_back(signal.t_s[k_impact]);
        if (first_only) break;
        first_value = p.value;
        first_sign = signal.w_B[p.index][1] >= 0.0 ? 1.0 : -1.0;
        // The attitude since the first impact (the base flat there: R = I), integrated with the exponential map
        // of the mean ω over each sample interval; the tilt about y is the elevation of the body x axis. In 3D
        // rocking with roll and spin, ∫ω_y dt drifts from it (by 0.03 rad over 0.37 s with 19° of roll).
        Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
        for (std::size_t k = k_impact + 1; k < signal.size(); ++k) {
          const Eigen::Vector3d turn = 0.5 * (signal.t_s[k] - signal.t_s[k - 1]) * (signal.w_B[k] + signal.w_B[k - 1]);
          const double angle = turn.norm();
          if (angle > 0.0) R = R * Eigen::AngleAxisd(angle, turn / angle).toRotationMatrix();
          tilt_y[k] = std::asin(std::clamp(R(2, 0), -1.0, 1.0));
          max_tilt_y[k] = std::max(max_tilt_y[k - 1], std::abs(tilt_y[k]));
        }
      }
    } else if (p.value >= options.later_impact_fraction * first_value && p.index + 1 < signal.size()) {
      // A base impact on the release side: the block rocks back (ω_y has the opposite sign of the landing from
      // the release) and |ω_y| drops abruptly after the peak. Smooth maxima of |ω_y| in 3D rocking on a
      // vertex and the jumps of edge impacts while rocking on the far side fail one of these tests.
      // It also happens with the base back near flat: the tilt about y since the first impact (flat there) is
      // small against its largest value in between; edge impacts between the far vertices V3, V4 happen at a
      // large tilt.
      const double w = signal.w_B[p.index][1];
      if (w * first_sign >= 0.0) continue;
      const ClippedTop top = ClippedTopAround(signal, p.index);
      auto impact_at = [&](std::size_t k, bool need_drop) {
        if (k == 0 || k + 1 >= signal.size()) return false;
        const double drop = std::abs(signal.w_B[k][1]) - std::abs(signal.w_B[k + 1][1]);
        const bool flat = std::abs(tilt_y[k]) <= options.flat_tilt_fraction * max_tilt_y[k];
        // The base passes through flat about y at the peak itself: the release side touches down there, whatever
        // the jump (an edge impact V3→V2 with λ < 1 changes ω_y by only a few per cent, and the sample after the
        // impact can be higher than the one before). "At the peak": within the tilt swept in kLandingSamples
        // samples, as the peak sample is the last before the impact or the first after it.
        const double one_sample_tilt =
            std::max(std::abs(tilt_y[k] - tilt_y[k - 1]), std::abs(tilt_y[k + 1] - tilt_y[k]));
        const bool lands_here = std::abs(tilt_y[k]) <= kLandingSamples * one_sample_tilt;
        return (flat && (!need_drop || drop >= options.min_jump_fraction * std::abs(w))) || lands_here;
      };
      if (!top.clipped) {
        if (impact_at(p.index, true)) times.push_back(signal.t_s[p.index]);
        continue;
      }
      // A clipped top hides the drop: the impact is at its end when |ω_y| drops right after it, else inside it,
      // where the base passes flat (at its middle, as FindPeaks places the peak, when the tilt says nowhere).
      if (impact_at(top.last, true)) {
        times.push_back(signal.t_s[top.last]);
        continue;
      }
      for (std::size_t k = top.first; k <= top.last; ++k) {
        if (impact_at(k, false)) {
          times.push_back(signal.t_s[p.index]);
          break;
        }
      }
    }
  }
  if (times.empty()) {
    throw BadInput(fmt::format("no impact found in the recording: |ω_y| has no peak with a prominence of {} rad/s; "
                               "check the mounting (--mounting) and that the recording contains a release",
                               options.detection.min_prominence_rad_s));
  }
  return times;
}

}  // namespace

std::vector<double> DetectBaseImpactTimes(const MeasuredSignal& signal, const InitialGuessOptions& options) {
  options.Validate();
  signal.Validate();
  return BaseImpactTimes(signal, options, false);
}

double DetectWindowEnd(const MeasuredSignal& signal, const InitialGuessOptions& options) {
  const std::vector<double> times = DetectBaseImpactTimes(signal, options);
  const std::size_t n = static_cast<std::size_t>(options.window_end_impact);
  return times.size() >= n ? times[n - 1] : signal.t_s.back();
}

namespace {

// The planar fall of phase 1 fitted to the samples before the first impact (the peak at k_peak, of sign `sign`).
struct Phase1Fit {
  double t0_s = 0.0;
  double alpha_rad = 0.0;
  double alpha_landing_rate_rad = 0.0;  // the coarse estimate from the landing rate
  double alpha_swept_rad = 0.0;         // the coarse estimate from the angle swept before the impact
};

Phase1Fit FitPhase1(const MeasuredSignal& signal, const core::PlanarRocker& rocker, std::size_t k_peak, double sign,
                    bool closed_form_fall) {
  Phase1Fit fit;
  const double dt = (signal.t_s.back() - signal.t_s.front()) / static_cast<double>(signal.size() - 1);
  const double alpha_max = rocker.critical_angle_rad * (1.0 - 1e-6);
  const double peak_rate = sign * signal.w_B[k_peak][1];
  const double alpha_coarse = std::min(AlphaFromLandingRate(rocker, peak_rate), alpha_max);
  const std::size_t k_last = k_peak - 1;  // before the impact whether the peak sample is just before or after it
  // The tilt swept in phase 1, ∫ω_y dt from the start of the recording to the impact (the block turns from α to
  // flat). Near the critical angle the landing rate hardly depends on α (dω⁻/dα → 0 as α → θ_c), so the
  // landing-rate estimate can be off by more than the search width below; the swept angle is not.
  double alpha_swept = 0.0;
  for (std::size_t k = 1; k <= k_last; ++k) {
    alpha_swept += 0.5 * (signal.t_s[k] - signal.t_s[k - 1]) * sign * (signal.w_B[k][1] + signal.w_B[k - 1][1]);
  }
  alpha_swept = std::clamp(alpha_swept, 1e-3, alpha_max);
  const double window_s = kPhase1WindowFactor * core::FallTime(rocker, std::max(alpha_coarse, alpha_swept));
  std::size_t k_first = 0;
  while (k_first < k_last && signal.t_s[k_first] < signal.t_s[k_peak] - window_s) ++k_first;

  // The samples of the window (clipped ones only say "at least this fast", gyro_clipping.hpp: left out).
  std::vector<double> t_fit_s, w_fit_rad_s;
  for (std::size_t k = k_first; k <= k_last; ++k) {
    if (signal.is_excluded(k)) continue;
    t_fit_s.push_back(signal.t_s[k]);
    w_fit_rad_s.push_back(sign * signal.w_B[k][1]);
  }
  auto cost_at = [&](const PlanarFallTable& fall, double t0) {
    double sum = 0.0;
    for (std::size_t n = 0; n < t_fit_s.size(); ++n) {
      const double d = w_fit_rad_s[n] - fall.Rate(t_fit_s[n] - t0);
      sum += d * d;
    }
    return sum;
  };
  // The minimum of f on [lo, hi]: by Brent's method with the closed-form fall, else by golden sections.
  auto minimum = [&](double lo, double hi, double tolerance, auto&& f) {
    return closed_form_fall ? BrentMinimum(lo, hi, tolerance, f) : GoldenMinimum(lo, hi, f);
  };
  const PlanarFallTable::Nodes nodes =
      closed_form_fall ? PlanarFallTable::Nodes::kClosedForm : PlanarFallTable::Nodes::kIntegrated;
  auto best_t0_for = [&](double alpha, double* cost) {
    const PlanarFallTable fall(rocker, alpha, nodes);
    const double t0_center = signal.t_s[k_peak] - fall.table_end_s();
    const double t0 = minimum(t0_center - 1.5 * dt, t0_center + 1.5 * dt, kPhase1T0ToleranceS,
                              [&](double t) { return cost_at(fall, t); });
    *cost = cost_at(fall, t0);
    return t0;
  };
  // A scan first: near the critical angle the fall is slow and the cost has several shallow minima in α.
  auto cost_of_alpha = [&](double a) {
    double c = 0.0;
    best_t0_for(a, &c);
    return c;
  };
  const double alpha_lo = std::max(1e-3, std::min(alpha_coarse, alpha_swept) - kAlphaSearchHalfWidthRad);
  const double alpha_hi = std::min(alpha_max, std::max(alpha_coarse, alpha_swept) + kAlphaSearchHalfWidthRad);
  // The scan keeps its step (2 mrad) when both estimates widen the interval.
  const int scan_points = std::max(
      kAlphaScanPoints, static_cast<int>(std::ceil(kAlphaScanPoints * (alpha_hi - alpha_lo) / (2.0 * kAlphaSearchHalfWidthRad))));
  const double alpha_step = (alpha_hi - alpha_lo) / scan_points;
  double best_scan = alpha_lo, best_scan_cost = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= scan_points; ++i) {
    const double a = alpha_lo + alpha_step * i;
    const double c = cost_of_alpha(a);
    if (c < best_scan_cost) {
      best_scan_cost = c;
      best_scan = a;
    }
  }
  fit.alpha_rad = minimum(std::max(alpha_lo, best_scan - alpha_step), std::min(alpha_hi, best_scan + alpha_step),
                          kPhase1AlphaToleranceRad, cost_of_alpha);
  double cost = 0.0;
  fit.t0_s = best_t0_for(fit.alpha_rad, &cost);
  fit.alpha_landing_rate_rad = alpha_coarse;
  fit.alpha_swept_rad = alpha_swept;
  return fit;
}

// ω⁺ after the first impact (x and y, in the sense of the fall): the medians of the first `samples` samples after
// t_impact, ω_y corrected for the planar deceleration about the far edge (the same |ψ̈| ≈ (K/2)·sin θ_c near the
// flat position) so that it refers to the impact instant. Clipped samples (gyro_clipping.hpp) are passed over.
Eigen::Vector2d RateAfterImpact(const MeasuredSignal& signal, const core::PlanarRocker& rocker, double t_impact,
                                double sign, int samples) {
  const double decel = 0.5 * rocker.K() * std::sin(rocker.critical_angle_rad);
  std::vector<double> wx, wy;
  for (std::size_t k = 0; k < signal.size() && static_cast<int>(wy.size()) < samples; ++k) {
    if (signal.t_s[k] <= t_impact || signal.is_excluded(k)) continue;  // clipped: only "at least this fast"
    wx.push_back(sign * signal.w_B[k][0]);
    wy.push_back(sign * signal.w_B[k][1] + decel * (signal.t_s[k] - t_impact));
  }
  if (wy.empty()) throw BadInput("the recording ends at the first impact: nothing after it to fit");
  return {UpperMedian(std::move(wx)), UpperMedian(std::move(wy))};
}

// The (λ_lat, λ_lon) whose facet impact map (18)+(21) sends ω⁻ = (0, landing rate, 0) closest to the measured ω⁺:
// a grid over the bounds, then a finer one around its best, λ_lat restricted to the sign of ω_x⁺. Returns the miss
// [rad/s] (infinite when no pair has a solution) and leaves the pair unchanged then.
double FitFacetPairToJump(const core::Block& block, const ParameterSet& parameters, core::FacetTauRule tau_rule,
                          double landing_rate_rad_s, const Eigen::Vector2d& w_plus, double* lambda_lat,
                          double* lambda_lon) {
  const Parameter& p_lat = parameters[ParameterId::kLambdaLat];
  const Parameter& p_lon = parameters[ParameterId::kLambdaLon];
  const Eigen::Vector3d w_minus(0.0, landing_rate_rad_s, 0.0);
  double best = std::numeric_limits<double>::infinity();
  double best_lat = *lambda_lat, best_lon = *lambda_lon;
  auto try_pair = [&](double lat, double lon) {
    core::FacetImpactParameters fp;
    fp.lambda_lat = lat;
    fp.lambda_lon = lon;
    fp.tau_rule = tau_rule;
    const core::ImpactOutcome out = core::FacetImpact(block, 2, w_minus, fp);
    if (out.status != core::ImpactStatus::kOk) return;
    const double d = std::hypot(out.w_plus_B.x() - w_plus.x(), out.w_plus_B.y() - w_plus.y());
    if (d < best) {
      best = d;
      best_lat = lat;
      best_lon = lon;
    }
  };
  constexpr int kGrid = 48;
  const bool positive = w_plus.x() >= 0.0;
  const double lat_lo = p_lat.fixed ? p_lat.value : (positive ? std::max(0.0, p_lat.lower) : p_lat.lower);
  const double lat_hi = p_lat.fixed ? p_lat.value : (positive ? p_lat.upper : std::min(0.0, p_lat.upper));
  const double lon_lo = p_lon.fixed ? p_lon.value : p_lon.lower;
  const double lon_hi = p_lon.fixed ? p_lon.value : p_lon.upper;
  for (int pass = 0; pass < 2; ++pass) {
    const double span_lat = pass == 0 ? (lat_hi - lat_lo) : 2.0 * (lat_hi - lat_lo) / kGrid;
    const double span_lon = pass == 0 ? (lon_hi - lon_lo) : 2.0 * (lon_hi - lon_lo) / kGrid;
    const double c_lat = pass == 0 ? 0.5 * (lat_lo + lat_hi) : best_lat;
    const double c_lon = pass == 0 ? 0.5 * (lon_lo + lon_hi) : best_lon;
    for (int i = 0; i <= kGrid; ++i) {
      for (int j = 0; j <= kGrid; ++j) {
        const double lat = std::clamp(c_lat - 0.5 * span_lat + span_lat * i / kGrid, lat_lo, lat_hi);
        const double lon = std::clamp(c_lon - 0.5 * span_lon + span_lon * j / kGrid, lon_lo, lon_hi);
        try_pair(lat, lon);
      }
    }
  }
  if (std::isfinite(best)) {
    *lambda_lat = best_lat;
    *lambda_lon = best_lon;
  }
  return best;
}

// The release from the first impact: the peak's sample, the sense of the fall and the phase-1 fit. Throws BadInput
// when the peak is at the start of the recording.
struct Release {
  std::size_t k_peak = 0;
  double sign = 1.0;
  Phase1Fit phase1;
};

Release FitRelease(const MeasuredSignal& signal, const core::PlanarRocker& rocker, double t_first_impact_s,
                   bool closed_form_fall) {
  Release release;
  release.k_peak = static_cast<std::size_t>(
      std::lower_bound(signal.t_s.begin(), signal.t_s.end(), t_first_impact_s) - signal.t_s.begin());
  if (release.k_peak < 3) throw BadInput("the first impact is at the start of the recording: the release is not recorded");
  release.sign = signal.w_B[release.k_peak][1] >= 0.0 ? 1.0 : -1.0;
  // Phase 1: a coarse α from the landing rate, then the planar fall fitted to the samples before the impact.
  release.phase1 = FitPhase1(signal, rocker, release.k_peak, release.sign, closed_form_fall);
  return release;
}

}  // namespace

ReleaseEstimate EstimateRelease(const MeasuredSignal& signal, const core::Block& block, const ParameterSet& base,
                                const InitialGuessOptions& options) {
  options.Validate();
  signal.Validate();
  ReleaseEstimate estimate;
  estimate.t_first_impact_s = BaseImpactTimes(signal, options, true).front();
  const core::PlanarRocker rocker = core::PlanarRockerAboutEdge(block, 1, 2);
  const Release release = FitRelease(signal, rocker, estimate.t_first_impact_s, options.closed_form_fall);
  // As SetValue in EstimateInitialGuess: the fixed value, else the fit clamped to the bounds.
  const Parameter& t0 = base[ParameterId::kT0];
  estimate.t0_s = t0.fixed ? t0.value : Clamp(t0, release.phase1.t0_s);
  return estimate;
}

InitialGuess EstimateInitialGuess(const MeasuredSignal& signal, const core::Block& block, const ParameterSet& base,
                                  const InitialGuessOptions& options) {
  options.Validate();
  signal.Validate();
  InitialGuess guess;
  guess.parameters = base;
  const std::vector<double> impacts = BaseImpactTimes(signal, options, false);
  guess.t_first_impact_s = impacts.front();
  const std::size_t n_end = static_cast<std::size_t>(options.window_end_impact);
  guess.t_end_s = impacts.size() >= n_end ? impacts[n_end - 1] : signal.t_s.back();
  if (impacts.size() > n_end) guess.later_impacts_s.assign(impacts.begin() + static_cast<std::ptrdiff_t>(n_end), impacts.end());

  const core::PlanarRocker rocker = core::PlanarRockerAboutEdge(block, 1, 2);
  const Release release = FitRelease(signal, rocker, guess.t_first_impact_s, options.closed_form_fall);
  const Phase1Fit& phase1 = release.phase1;
  const double sign = release.sign;
  const double t_impact = phase1.t0_s + core::FallTime(rocker, phase1.alpha_rad);
  guess.landing_rate_rad_s = core::LandingRate(rocker, phase1.alpha_rad);
  SetValue(&guess.parameters, ParameterId::kT0, phase1.t0_s);
  SetValue(&guess.parameters, ParameterId::kAlpha, phase1.alpha_rad);
  guess.notes.push_back(fmt::format("first impact at {:.4f} s; planar phase-1 fit: t0 = {:.4f} s, α = {:.4f} rad "
                                    "(landing-rate estimate {:.4f} rad, swept angle {:.4f} rad)",
                                    guess.t_first_impact_s, phase1.t0_s, phase1.alpha_rad,
                                    phase1.alpha_landing_rate_rad, phase1.alpha_swept_rad));

  // The first jump: λ_lon by the inverse of (6), the sign of λ_lat from ω_x⁺.
  const Eigen::Vector2d w_plus = RateAfterImpact(signal, rocker, t_impact, sign, options.post_impact_samples);
  guess.jump_ratio = w_plus.y() / guess.landing_rate_rad_s;
  const core::PlanarBlock planar = core::PlanarBlockAboutY(block);
  double lambda_lon = guess.jump_ratio != -1.0 ? core::LambdaFromAvrf(planar, guess.jump_ratio)  // inverse of (6)
                                               : guess.parameters.value(ParameterId::kLambdaLon);
  double lambda_lat = w_plus.x() >= 0.0 ? 1.0 : -1.0;
  guess.notes.push_back(fmt::format("first jump r = ω_y⁺/ω_y⁻ = {:.4f} → λ_lon = {:.3f} by the inverse of (6); "
                                    "ω_x⁺ = {:.3f} rad/s → sign of λ_lat {}", guess.jump_ratio, lambda_lon, w_plus.x(),
                                    w_plus.x() >= 0.0 ? "+" : "−"));

  // Refine (λ_lat, λ_lon) with the facet impact map.
  const double miss = FitFacetPairToJump(block, guess.parameters, base.facet_tau_rule(), guess.landing_rate_rad_s,
                                         w_plus, &lambda_lat, &lambda_lon);
  if (std::isfinite(miss)) {
    guess.notes.push_back(fmt::format("facet map fit of ω⁺: λ_lat = {:.3f}, λ_lon = {:.3f} (miss {:.3f} rad/s)",
                                      lambda_lat, lambda_lon, miss));
  }
  SetValue(&guess.parameters, ParameterId::kLambdaLat, lambda_lat);
  SetValue(&guess.parameters, ParameterId::kLambdaLon, lambda_lon);
  SetValue(&guess.parameters, ParameterId::kLambda, options.default_lambda);
  guess.notes.push_back(fmt::format("λ = {} (default; the global stage scans it once edge impacts act)",
                                    options.default_lambda));
  return guess;
}

}  // namespace rockfit::fitting
