// The error function (28) of the paper (Sect. 5.1), exactly as docs/design.md §7 defines it:
//
//   ε(t0, α, …) = (t_end − t0)⁻¹ ∫_{t0}^{t_end} ‖ω_m(t) − ω_s(t − t0)‖₂ dt,
//
// with the trapezoid rule on the nodes t0 < t_k < t_end, where t_k are the measured sample times, the measured
// value at t0 (and at t_end when it is not a sample) is interpolated linearly, and ω_s is the model sampled at
// exactly these node times minus t0 (never re-interpolated). A node enters at t0 with the value the sample
// it replaces would have, so ε does not jump when t0 crosses a sample time.
//
// Samples marked excluded (the gyro clipped at its full scale, gyro_clipping.hpp) get no weight — nor does an
// end node interpolated from one — and ε is the mean over the time that the remaining weights cover; unless
// they are marked censored too, then they keep their weight and enter with the censored misfit of NodeMisfit.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace rockfit::fitting {

// Measured angular velocity of one trial in recording time.
struct MeasuredSignal {
  std::vector<double> t_s;           // strictly increasing [s]
  std::vector<Eigen::Vector3d> w_B;  // [rad/s], one per time
  // Empty, or one per sample: true leaves the sample out of (28) and of the noise floor at rest (a clipped gyro,
  // gyro_clipping.hpp).
  std::vector<bool> excluded;
  // Empty, or one per sample: bit a set when axis a sat at the gyro's rail (clipped), so the recorded value says
  // only "at least this fast, in this sense". A sample with a censored axis enters (28) with the censored
  // misfit of NodeMisfit instead of being left out (the phase-1 estimate and the noise floor still pass over it
  // when it is also excluded).
  std::vector<std::uint8_t> censored_axes;

  bool is_excluded(std::size_t k) const { return !excluded.empty() && excluded[k]; }
  std::uint8_t censored_at(std::size_t k) const { return censored_axes.empty() ? 0 : censored_axes[k]; }
  // Throws InvalidArgument when sizes differ (also of `excluded` when not empty), fewer than two samples, a value is not finite, or time does not
  // strictly increase (naming the first offending sample).
  void Validate() const;
  std::size_t size() const { return t_s.size(); }
  // Linear interpolation of w_B at t, clamped to the first/last sample outside the recording.
  Eigen::Vector3d Interpolate(double t) const;
};

// The quadrature nodes of (28) for one t0.
struct ErrorNodes {
  std::vector<double> t_s;                  // t_s[0] = t0 < … < t_s.back() = t_end (recording time)
  std::vector<double> t_after_release_s;    // t_s − t0, where the model is sampled (starts at 0)
  std::vector<Eigen::Vector3d> w_m_B;       // measured ω at the nodes
  std::vector<double> weight_s;             // trapezoid weights; with excluded_weight_s they sum to t_end − t0
  double excluded_weight_s = 0.0;           // the trapezoid weight of the excluded nodes (set to 0 in weight_s)
  std::size_t num_excluded = 0;             // nodes whose weight was excluded
  std::vector<std::uint8_t> censored_axes;  // per node: the censored axes of its sample (0: a plain measurement)
  std::size_t num_censored = 0;             // nodes with a censored axis
  std::size_t first_sample = 0;             // signal index of node 1 when node 1 is a sample
  std::size_t num_interior = 0;             // nodes 1..num_interior are the samples strictly inside (t0, t_end)

  std::size_t size() const { return t_s.size(); }
  double duration_s() const { return t_s.back() - t_s.front(); }
  // The time the weights cover, (28)'s divisor: duration_s() less the excluded weight.
  double weighted_duration_s() const { return duration_s() - excluded_weight_s; }
};

// Fills `nodes` (reusing its storage) for the window [t0, t_end]. Returns false when the window is empty or
// not inside the recording: t0 < t_front, t_end > t_back or t0 ≥ t_end.
bool BuildErrorNodes(const MeasuredSignal& signal, double t0_s, double t_end_s, ErrorNodes* nodes);

// The misfit ω_m − ω_s of node i, censored on the axes where the gyro sat at its rail: there the recording says
// only s·ω ≥ s·ω_m (s the sign of ω_m), so the component is 0 when the model is at or beyond the rail in the same
// sense and ω_m − ω_s (the model falls short) otherwise — the one-sided residual of a censored observation
// (fitting/README.md, "Clipped gyro samples").
Eigen::Vector3d NodeMisfit(const ErrorNodes& nodes, std::size_t i, const Eigen::Vector3d& w_s_B);

// The censored axes of node i whose observation the model satisfies (at or beyond the rail, bit a for axis a):
// there NodeMisfit is 0 whatever the model does nearby, so the component is no residual — it has no value to
// scatter about and its Jacobian row is 0. The intervals leave such components out of their degrees of freedom.
std::uint8_t SatisfiedCensoredAxes(const ErrorNodes& nodes, std::size_t i, const Eigen::Vector3d& w_s_B);
// The number of such components over the nodes with weight, for the model's ω_s at the nodes (same length).
std::size_t NumSatisfiedCensoredComponents(const ErrorNodes& nodes, const std::vector<Eigen::Vector3d>& w_s_B);

// (28) for the nodes and the model's ω_s at nodes.t_after_release_s (same length); +∞ when every node is excluded.
double TrajectoryError(const ErrorNodes& nodes, const std::vector<Eigen::Vector3d>& w_s_B);

}  // namespace rockfit::fitting
