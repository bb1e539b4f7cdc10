// The impact time inside its sample interval from where a levelled angle comes back to zero (io/README.md,
// "Attitude from the gyro", "Where in the interval").
//
// The angle integrated from the gyro is the gyro's own sum over the samples: it holds no information on where
// inside the sample interval the rate jumped, so the anchor fit (impact_anchor.hpp) places an impact seen in it
// near the interval's middle, and the anchor read there is off by up to ω⁻·Δt/2. But such an angle is levelled
// (by the accelerometer at rest, or at the first impact) and has the rest's gyro bias removed, so its error E(t)
// changes little over a second, and the true angle is zero at the impact. The impact time τ is therefore where
// the angle minus an estimate Ê of E crosses zero. From the last sample m before the impact the angle goes on as
//     φ(t_m + s) = φ_m + a·s + ½·b·s²,
// a + b·s the least-squares line through the Euler rates of the samples m − K + 1 … m, so τ = t_m + s with
//     φ_m + a·s + ½·b·s² − Ê = 0,   0 ≤ s ≤ Δt,
// exact for a rate linear in time before the impact and an error E = Ê there. Each impact reads E at its
// interval's middle, φ(t_mid) − E(τ) = a·(t_mid − τ), uniform within ±|a|·Δt/2; Ê is the mean of these readings
// within a window, each weighted by the inverse of its variance a²·Δt²/12 + σ₀² (σ₀ the scatter they show besides,
// from the ringing of neighbouring impacts), so that the small late impacts, whose readings are the sharpest,
// fix E for the large early ones. An error e of Ê moves τ by e/|a|, and the anchor read at τ from an angle
// integrated with the interval split there is then off by e, where it was off by up to |a|·Δt/2.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

namespace rockfit::io {

struct ZeroCrossingOptions {
  // Samples before the impact through which the rate line is fitted: 4 = 12 ms at 256 Hz (3 intervals), short
  // against the quarter period of the smallest rocking the detector keeps, long enough to average the gyro noise.
  std::size_t rate_fit_samples = 4;
  // Half-width of the window of readings averaged into Ê [s]: 1 s holds several impacts even at the start of the
  // rocking, where they are furthest apart, and a residual gyro bias of 10⁻⁴ rad/s moves E by 10⁻⁴ rad over it.
  double drift_half_window_s = 1.0;
  // σ₀, the scatter of a reading of E besides its place in the interval [rad]: ±10⁻³ rad seen in the cascade of
  // small impacts of the sample trial with the most out-of-plane motion (io/README.md).
  double reading_scatter_rad = 1e-3;
  // Throws InvalidArgument naming the bad option.
  void Validate() const;
};

// A reading of the angle's error E: its time [s], value [rad] and weight (> 0, the inverse of its variance).
struct DriftPoint {
  double t_s = 0.0;
  double value_rad = 0.0;
  double weight = 1.0;
};

// Ê at t_s: the weighted mean of the points within ±half_window_s of t_s; the nearest point's value when none is
// within the window; 0 without points.
double SmoothDriftAt(const std::vector<DriftPoint>& points, double t_s, double half_window_s);

// The angle in the sample interval [t_m, t_m+1] holding an impact as the samples before it continue it (above).
struct BeforeImpact {
  double t0_s = 0.0, t1_s = 0.0;   // t_m, t_m+1
  double angle_rad = 0.0;          // φ_m
  double rate_rad_s = 0.0;         // a
  double rate_slope_rad_s2 = 0.0;  // b
  double At(double t_s) const {
    const double s = t_s - t0_s;
    return angle_rad + s * (rate_rad_s + 0.5 * rate_slope_rad_s2 * s);
  }
  // The reading of E at the interval's middle, weighted by the inverse of its variance a²·Δt²/12 + σ₀².
  DriftPoint MiddleReading(double reading_scatter_rad) const;
};

// nullopt when m has fewer than K − 1 samples before it or none after it. `rate_rad_s` is the angle's rate from
// the gyro, the same length as `t_s` and `angle_rad`.
std::optional<BeforeImpact> AngleBeforeImpact(const std::vector<double>& t_s, const std::vector<double>& angle_rad,
                                              const std::vector<double>& rate_rad_s, std::size_t m,
                                              const ZeroCrossingOptions& options);

// The time in [t_m, t_m+1] where before.At(t) − drift_rad crosses zero; nullopt when it does not inside the
// interval (the impact is not in it, or the error is not known well enough there to tell).
std::optional<double> ZeroCrossingTime(const BeforeImpact& before, double drift_rad);

}  // namespace rockfit::io
