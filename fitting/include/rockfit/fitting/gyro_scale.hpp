// A gyro scale factor estimated inside the fit by variable projection (fitting/README.md, "A gyro scale in the
// fit"). A real gyro reads ω_m = S·ω + noise with S = diag(s_x, s_y, s_z) a percent or two off the identity.
// The model's ω_s enters S·ω_s linearly, so for fixed (t0, α, λ's) the scale that fits best has a closed form,
// the weighted least-squares value on the nodes of (28) (trapezoid weights w_k):
//
//   per axis a:  s_a = Σ_k w_k ω_m,a,k ω_s,a,k / Σ_k w_k ω_s,a,k²
//   common:      s   = Σ_k w_k ω_m,k · ω_s,k   / Σ_k w_k ‖ω_s,k‖²
//
// clamped to [1 − kMaxGyroScaleError, 1 + kMaxGyroScaleError] (per axis, the constrained minimiser of a
// one-dimensional quadratic). The objective then evaluates (28) of the scaled model, ε = mean ‖ω_m − S·ω_s‖, and
// every stage — search, identifiability, intervals, model-error statement — sees the scale projected out: its
// uncertainty enters the other parameters' through the Jacobian and the profiles of the projected residuals.
// The closed form minimises the sum of squares behind (28) (the form the Ceres back end and the intervals use),
// not (28) itself, which weighs residuals by their norm; the two optima differ at second order.
// An axis reading censored at the gyro's rail (trajectory_error.hpp) is left out of both sums: it bounds ω,
// it does not measure S·ω.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "rockfit/fitting/trajectory_error.hpp"

namespace rockfit::fitting {

//  kOff:     S = I, the model's ω as it is (the default).
//  kCommon:  S = s·I, one scale for the three axes.
//  kPerAxis: S = diag(s_x, s_y, s_z), one per body axis.
enum class GyroScaleMode { kOff, kCommon, kPerAxis };
const char* ToString(GyroScaleMode mode);                     // "off", "common", "per-axis"
bool FromString(std::string_view text, GyroScaleMode* value);  // the inverse of ToString
GyroScaleMode ParseGyroScaleMode(const std::string& name);    // throws InvalidArgument naming the choices

// The largest scale error the projection accepts: gyro data sheets give a few percent at most; a scale off by
// more than 10 % is a wrong unit or range setting, not a calibration error, and a bound keeps the projection
// from blowing up a nearly silent axis in a short window.
constexpr double kMaxGyroScaleError = 0.1;

// Σ w_k ω_s,a² below this fraction of Σ w_k ‖ω_s‖² leaves axis a at 1 [1]: the model does not move about it, so
// the data cannot fix its scale (double round-off of the sums is ~1e-16 relative).
constexpr double kSilentAxisFraction = 1e-12;

// The scale of the header comment for the nodes and the model's ω_s at them (same length); (1, 1, 1) for kOff.
Eigen::Vector3d ProjectedGyroScale(const ErrorNodes& nodes, const std::vector<Eigen::Vector3d>& w_s_B,
                                   GyroScaleMode mode);

}  // namespace rockfit::fitting
