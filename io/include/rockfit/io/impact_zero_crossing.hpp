// The angle before an impact continued into the sample interval that holds it (io/README.md, "Attitude from the
// gyro", "Where in the interval").
//
// The angle integrated from the gyro is the gyro's own sum over the samples: it holds no information on where
// inside the sample interval the rate jumped, so the anchor fit (impact_anchor.hpp) places an impact seen in it
// near the interval's middle, and the anchor read there is off by up to ω⁻·Δt/2. But such an angle is levelled
// (by the accelerometer at rest, or at the first impact) and has the rest's gyro bias removed, so its error E(t)
// changes little between impacts, and the true angle is zero at the impact: the impact time τ is where the angle
// minus E comes back to zero. From the last sample m before the impact the angle goes on as
//     φ(t_m + s) = φ_m + a·s + ½·b·s²,
// a + b·s the least-squares line through the Euler rates of the samples m − K + 1 … m, exact for a rate linear in
// time before the impact. Read at the interval's middle it gives φ(t_mid) = E(τ) + a·(t_mid − τ): one equation
// for E and τ at each impact, which joint_impact_times.hpp solves for all impacts together.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

namespace rockfit::io {

struct ZeroCrossingOptions {
  // Samples before the impact through which the rate line is fitted: 4 = 12 ms at 256 Hz (3 intervals), short
  // against the quarter period of the smallest rocking the detector keeps, long enough to average the gyro noise.
  std::size_t rate_fit_samples = 4;
  // Throws InvalidArgument naming the bad option.
  void Validate() const;
};

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
  // The continued rate a + b·(t − t_m) [rad/s].
  double RateAt(double t_s) const { return rate_rad_s + rate_slope_rad_s2 * (t_s - t0_s); }
};

// nullopt when m has fewer than K − 1 samples before it or none after it. `rate_rad_s` is the angle's rate from
// the gyro, the same length as `t_s` and `angle_rad`.
std::optional<BeforeImpact> AngleBeforeImpact(const std::vector<double>& t_s, const std::vector<double>& angle_rad,
                                              const std::vector<double>& rate_rad_s, std::size_t m,
                                              const ZeroCrossingOptions& options);

}  // namespace rockfit::io
