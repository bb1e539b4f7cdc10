// Where exactly an impact happened, and the value of a drifting Euler angle there (the "anchor" of the drift
// correction, docs/design.md §6).
//
// The sample where |ω| peaks is within one sample period Δt of the impact, and the angle there differs from
// the angle at the impact by up to |ω|·Δt (4e-3 rad at 1 rad/s and 256 Hz) — as much as the drift we remove,
// and enough to spoil the AVRF of the small late peaks. The sub-sample estimate uses that the true angle is
// zero at the impact time τ and is the integral of its Euler rate φ̇ (from the gyro) on either side, while
// the drift d is smooth. Around the peak sample we fit, for every candidate τ in the two sample intervals next
// to the peak,
//     φ_m(t_j) = d(τ) + ρ·(t_j − τ) + ∫_τ^t_j P(t) dt,
// where P is a least-squares parabola through the rate samples before τ (for t < τ) or after τ (for t > τ),
// and ρ is the local drift rate. d(τ) and ρ follow by linear least squares; the τ with the smallest residual
// is the impact, and d(τ) the anchor. The rate jumps at the impact (ω⁺ = r·ω⁻), so a wrong τ leaves a residual
// that grows with the jump; where the jump is below `min_rate_jump_rad_s` the impact is not located inside the
// interval and the middle of the interval after the peak sample is used.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

namespace rockfit::io {

struct AnchorFitOptions {
  // Samples on each side of the impact used in the fit (at least 3, for the rate parabolas).
  std::size_t half_window_samples = 5;
  // A rate jump smaller than this does not locate the impact inside its sample interval [rad/s].
  double min_rate_jump_rad_s = 0.01;
  void Validate() const;
};

struct AnchorEstimate {
  double t_s = 0.0;          // impact time
  double value_rad = 0.0;    // measured (drifting) angle at t_s
  bool subsample = false;    // false: the sample value at the peak (too close to the ends of the recording)
  bool located = false;      // the rate jump located the impact inside its interval (else its middle is used)
  double rate_jump_rad_s = 0.0;    // |ω⁻| − |ω⁺| of the rate parabolas at t_s
  double rms_residual_rad = 0.0;   // of the angle fit
};

// `angle` is the measured Euler angle, `rate` its Euler rate from the gyro (same length as t). `peak_index` is
// the sample of the |ω| peak. With `known_t_s` the impact time is given (e.g. from |ω_y| for φ_x) and only the
// value is estimated.
AnchorEstimate EstimateAnchor(const std::vector<double>& t_s, const std::vector<double>& angle_rad,
                              const std::vector<double>& rate_rad_s, std::size_t peak_index,
                              const AnchorFitOptions& options, std::optional<double> known_t_s = std::nullopt);

}  // namespace rockfit::io
