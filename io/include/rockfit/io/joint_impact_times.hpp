// The impact times inside their sample intervals, estimated in one linear solve together with the error of the
// angle integrated from the gyro (io/README.md, "Attitude from the gyro", "Where in the interval").
//
// The angle Φ integrated by the mean rule (gyro_attitude.hpp) puts each rate jump in the middle of its sample
// interval [t_m, t_m+1]: against the angle integrated with that interval split at the impact τ it carries, from
// t_m+1 on, the step c·δ, with δ = t_mid − τ and c = ρ_m − ρ_m+1 the jump of the angle's rate samples (exact
// for one axis; to first order on SO(3)). Continued from the samples before impact k (impact_zero_crossing.hpp)
// to its interval's middle, Φ reads
//     y_k = E_k + a_k·δ_k + Σ_{j<k} c_j·δ_j,
// E_k the error of the angle split at every true impact (the gyro's bias and noise: slowly varying), a_k the
// continued rate, the sum over the splits before k: the true angle is zero at τ_k. Each axis adds its own
// readings with its own c_j; the δ_j are shared. The unknowns δ_j and E_k follow by generalised least squares
// with the priors
//     δ_j ~ N(0, Δt_j²/12)                                (τ anywhere in its interval),
//     E_k − E_k−1 − β·(t_k − t_k−1) ~ N(0, σ_w²·(t_k − t_k−1))   (a random walk about a residual bias β),
// and a reading scatter σ₀ (the ringing of earlier impacts and out-of-plane motion in the rate line). A small
// late impact (|a_k|·Δt below σ₀) cannot explain its reading by its δ_k and pins E there; a large early one takes
// its δ_k from E carried to it by the walk. Linear: no passes, no fixed point to wait for.
#pragma once

#include <cstddef>
#include <vector>

namespace rockfit::io {

struct JointImpactOptions {
  // σ₀, the scatter of a reading about the model [rad]: what the rate line continues wrongly (ringing left from
  // the impact before, out-of-plane motion). 2·10⁻⁴ rad: chosen on the sample campaign and the 48 synthetic trials
  // of seed 29, among 0.5–10·10⁻⁴ (io/README.md, "Where in the interval").
  double reading_scatter_rad = 2e-4;
  // σ_w, the random walk of the error between impacts [rad/√s]: a gyro white noise of 0.1 °/s at 256 Hz walks
  // 1.1·10⁻⁴ rad/√s. 10⁻⁴: chosen with σ₀ among 0.5–30·10⁻⁴.
  double drift_walk_rad_per_sqrt_s = 1e-4;
  // Throws InvalidArgument naming the bad option.
  void Validate() const;
};

// The sample interval [t0_s, t1_s] holding one impact; splits are given in time order, not overlapping.
struct SplitInterval {
  double t0_s = 0.0;
  double t1_s = 0.0;
  double middle_s() const { return 0.5 * (t0_s + t1_s); }
};

// One angle's reading of its error at the impact in split `split`: Φ continued from the samples before it to
// the interval's middle (angle_rad) and the continued rate there (rate_rad_s).
struct SplitReading {
  std::size_t split = 0;
  double angle_rad = 0.0;
  double rate_rad_s = 0.0;
};

// One angle (φ_y or φ_x): its readings in time order (at most one per split) and, for every split, the jump
// ρ_m − ρ_m+1 of its rate samples across that interval [rad/s].
struct AxisReadings {
  std::vector<SplitReading> readings;
  std::vector<double> rate_jump_rad_s;
};

struct JointImpactSummary {
  std::vector<double> offsets_s;  // δ_j = t_mid − τ_j, each within ±Δt_j/2
  std::vector<double> times_s;    // τ_j = t_mid − δ_j, inside its interval
  std::vector<std::vector<double>> errors_rad;  // Ê_k of each axis at its readings
};

// The estimate above. Throws InvalidArgument for splits that are not increasing, a reading naming no split,
// readings not in time order, or a rate_jump_rad_s whose length is not the number of splits.
JointImpactSummary EstimateJointImpactTimes(const std::vector<SplitInterval>& splits,
                                            const std::vector<AxisReadings>& axes, const JointImpactOptions& options);

}  // namespace rockfit::io
