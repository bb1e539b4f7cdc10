#include "rockfit/io/impact_anchor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/Dense>

#include "rockfit/core/errors.hpp"

namespace rockfit::io {

void AnchorFitOptions::Validate() const {
  if (half_window_samples < 3) {
    throw InvalidArgument("anchor fit half_window_samples must be at least 3, got " +
                          std::to_string(half_window_samples));
  }
  if (!std::isfinite(min_rate_jump_rad_s) || min_rate_jump_rad_s < 0.0) {
    throw InvalidArgument("anchor fit min_rate_jump_rad_s must be a finite number ≥ 0 [rad/s]");
  }
}

namespace {

// Candidate impact times scanned per sample interval before the golden-section polish.
constexpr int kScanPerInterval = 32;
// Golden-section steps: the bracket shrinks to 0.618^60 ≈ 3e-13 of one scan cell.
constexpr int kGoldenSteps = 60;

// A least-squares parabola through rate samples, τ measured from `origin`.
struct RateParabola {
  double origin = 0.0;
  double c0 = 0.0, c1 = 0.0, c2 = 0.0;
  double At(double t) const {
    const double tau = t - origin;
    return c0 + tau * (c1 + tau * c2);
  }
  // ∫_from^to of the parabola.
  double Integral(double from, double to) const {
    const auto primitive = [&](double t) {
      const double x = t - origin;
      return x * (c0 + x * (c1 / 2.0 + x * c2 / 3.0));
    };
    return primitive(to) - primitive(from);
  }
};

RateParabola FitRateParabola(const std::vector<double>& t, const std::vector<double>& rate, std::size_t first,
                             std::size_t count) {
  RateParabola parabola;
  parabola.origin = t[first + count - 1];
  Eigen::MatrixXd design(count, 3);
  Eigen::VectorXd values(count);
  for (std::size_t row = 0; row < count; ++row) {
    const double tau = t[first + row] - parabola.origin;
    design.row(static_cast<Eigen::Index>(row)) << 1.0, tau, tau * tau;
    values[static_cast<Eigen::Index>(row)] = rate[first + row];
  }
  const Eigen::Vector3d c = design.colPivHouseholderQr().solve(values);
  parabola.c0 = c[0];
  parabola.c1 = c[1];
  parabola.c2 = c[2];
  return parabola;
}

// The model fitted on the window for the impact inside the interval (t_m, t_m+1).
class IntervalModel {
 public:
  IntervalModel(const std::vector<double>& t, const std::vector<double>& angle, const std::vector<double>& rate,
                std::size_t m, std::size_t half_window)
      : t_(t), angle_(angle), m_(m) {
    const std::size_t n = t.size();
    lo_ = m + 1 - std::min(half_window, m + 1);
    hi_ = std::min(n - 1, m + half_window);
    ok_ = m - lo_ + 1 >= 3 && hi_ - m >= 3;
    if (!ok_) return;
    before_ = FitRateParabola(t, rate, lo_, m - lo_ + 1);
    after_ = FitRateParabola(t, rate, m + 1, hi_ - m);
  }
  bool ok() const { return ok_; }
  double t_begin() const { return t_[m_]; }
  double t_end() const { return t_[m_ + 1]; }

  struct Fit {
    double rss = std::numeric_limits<double>::infinity();
    double drift_at_tau = 0.0;  // d(τ)
    double rate_jump = 0.0;     // |ω⁻| − |ω⁺|
  };

  // Least squares for d(τ), ρ at a given impact time τ in [t_m, t_m+1].
  Fit Evaluate(double tau) const {
    double s11 = 0.0, s12 = 0.0, s22 = 0.0, b1 = 0.0, b2 = 0.0;
    const std::size_t count = hi_ - lo_ + 1;
    for (std::size_t j = lo_; j <= hi_; ++j) {
      const double swept = j <= m_ ? -before_.Integral(t_[j], tau) : after_.Integral(tau, t_[j]);
      const double y = angle_[j] - swept;
      const double x = t_[j] - tau;
      s11 += 1.0, s12 += x, s22 += x * x, b1 += y, b2 += x * y;
    }
    const double det = s11 * s22 - s12 * s12;
    Fit fit;
    if (!(det > 0.0)) return fit;
    const double d = (s22 * b1 - s12 * b2) / det;
    const double rho = (s11 * b2 - s12 * b1) / det;
    double rss = 0.0;
    for (std::size_t j = lo_; j <= hi_; ++j) {
      const double swept = j <= m_ ? -before_.Integral(t_[j], tau) : after_.Integral(tau, t_[j]);
      const double r = angle_[j] - swept - d - rho * (t_[j] - tau);
      rss += r * r;
    }
    fit.rss = rss / static_cast<double>(count);
    fit.drift_at_tau = d;
    fit.rate_jump = std::abs(before_.At(tau)) - std::abs(after_.At(tau));
    return fit;
  }

 private:
  const std::vector<double>& t_;
  const std::vector<double>& angle_;
  std::size_t m_;
  std::size_t lo_ = 0, hi_ = 0;
  bool ok_ = false;
  RateParabola before_, after_;
};

struct Located {
  double tau = 0.0;
  IntervalModel::Fit fit;
};

// The τ of smallest residual inside one interval among those where the impact loses energy (|ω⁻| > |ω⁺|):
// where the rate changes slope at the impact, a second τ with |ω⁺| > |ω⁻| can explain the samples equally
// well. A scan, then golden section around the best cell.
Located MinimizeInInterval(const IntervalModel& model) {
  const auto objective = [&](double tau, IntervalModel::Fit* out = nullptr) {
    const IntervalModel::Fit fit = model.Evaluate(tau);
    if (out) *out = fit;
    return fit.rate_jump > 0.0 ? fit.rss : std::numeric_limits<double>::infinity();
  };
  const double a = model.t_begin(), b = model.t_end();
  const double cell = (b - a) / kScanPerInterval;
  Located best;
  double best_value = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= kScanPerInterval; ++i) {
    const double tau = a + cell * i;
    IntervalModel::Fit fit;
    const double value = objective(tau, &fit);
    if (value < best_value) best = {tau, fit}, best_value = value;
  }
  if (!std::isfinite(best_value)) return {};
  double lo = std::max(a, best.tau - cell), hi = std::min(b, best.tau + cell);
  const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = hi - golden * (hi - lo), x2 = lo + golden * (hi - lo);
  double f1 = objective(x1), f2 = objective(x2);
  for (int step = 0; step < kGoldenSteps; ++step) {
    if (f1 < f2) {
      hi = x2, x2 = x1, f2 = f1;
      x1 = hi - golden * (hi - lo);
      f1 = objective(x1);
    } else {
      lo = x1, x1 = x2, f1 = f2;
      x2 = lo + golden * (hi - lo);
      f2 = objective(x2);
    }
  }
  IntervalModel::Fit polished;
  const double tau = 0.5 * (lo + hi);
  if (objective(tau, &polished) <= best_value) best = {tau, polished};
  return best;
}

}  // namespace

AnchorEstimate EstimateAnchor(const std::vector<double>& t_s, const std::vector<double>& angle_rad,
                              const std::vector<double>& rate_rad_s, std::size_t peak_index,
                              const AnchorFitOptions& options, std::optional<double> known_t_s) {
  options.Validate();
  const std::size_t n = t_s.size();
  if (angle_rad.size() != n || rate_rad_s.size() != n || peak_index >= n) {
    throw InvalidArgument("EstimateAnchor: time, angle and rate must have the same length and contain the peak");
  }
  AnchorEstimate estimate;
  estimate.t_s = t_s[peak_index];
  estimate.value_rad = angle_rad[peak_index];

  if (known_t_s) {
    const auto upper = std::upper_bound(t_s.begin(), t_s.end(), *known_t_s);
    if (upper == t_s.begin() || upper == t_s.end()) return estimate;
    const IntervalModel model(t_s, angle_rad, rate_rad_s, static_cast<std::size_t>(upper - t_s.begin()) - 1,
                              options.half_window_samples);
    if (!model.ok()) return estimate;
    const IntervalModel::Fit fit = model.Evaluate(*known_t_s);
    estimate.t_s = *known_t_s;
    estimate.value_rad = fit.drift_at_tau;
    estimate.subsample = true;
    estimate.located = true;
    estimate.rate_jump_rad_s = fit.rate_jump;
    estimate.rms_residual_rad = std::sqrt(fit.rss);
    return estimate;
  }

  // The impact is in the interval after the peak sample, or — when ringing or r ≈ 1 puts the peak on the
  // first sample after the impact — in the one before it.
  Located best;
  std::optional<IntervalModel> after_peak;
  for (std::size_t m : {peak_index, peak_index - 1}) {
    if (m + 1 >= n || (m == peak_index - 1 && peak_index == 0)) continue;
    IntervalModel model(t_s, angle_rad, rate_rad_s, m, options.half_window_samples);
    if (!model.ok()) continue;
    const Located located = MinimizeInInterval(model);
    if (located.fit.rss < best.fit.rss) best = located;
    if (m == peak_index) after_peak.emplace(model);
  }
  if (best.fit.rss < std::numeric_limits<double>::infinity() && best.fit.rate_jump >= options.min_rate_jump_rad_s) {
    estimate.located = true;
  } else if (after_peak) {
    best.tau = 0.5 * (after_peak->t_begin() + after_peak->t_end());
    best.fit = after_peak->Evaluate(best.tau);
  } else {
    return estimate;
  }
  estimate.subsample = true;
  estimate.t_s = best.tau;
  estimate.value_rad = best.fit.drift_at_tau;
  estimate.rate_jump_rad_s = best.fit.rate_jump;
  estimate.rms_residual_rad = std::sqrt(best.fit.rss);
  return estimate;
}

}  // namespace rockfit::io
