// A gyro scale factor estimated inside the fit by variable projection (fitting/README.md, "A gyro scale in the
// fit"). A real gyro reads ω_m = S·ω + noise with S = diag(s_x, s_y, s_z) a percent or two off the identity.
// For fixed (t0, α, λ's) the model's ω_s at the nodes of (28) are fixed, and the scale the fit uses is the one
// that minimises (28) itself over the admissible box [1 − kMaxGyroScaleError, 1 + kMaxGyroScaleError]:
//
//   F(S) = Σ_k w_k ‖d_k(S)‖,   d_k(S) = NodeMisfit(k, S·ω_s,k)      ((28) = F / the covered time, a constant)
//
// with w_k the trapezoid weights and the censored one-sided misfit on axes at the gyro's rail. Each ‖d_k‖ is a
// norm of components that are affine in S (or the positive part of one, censored), so F is convex in S and its
// minimiser on the box is found by a safeguarded Newton iteration on the slope
//
//   dF/ds = −Σ_k w_k (Σ_{a∈A} d_k,a ω_s,k,a) / ‖d_k‖        (A: the axes s scales)
//   d²F/ds² = Σ_k w_k [Σ_{a∈A, active} ω_s,k,a² / ‖d_k‖ − (Σ_{a∈A} d_k,a ω_s,k,a)² / ‖d_k‖³]  ≥ 0
//
// (a censored component is active while the model falls short of the rail; a node with d_k = 0 contributes the
// subgradient 0). It starts from the weighted least-squares scale (LeastSquaresGyroScale), keeps a bracket
// [lo, hi] on which the slope changes sign, takes a Newton step when it stays inside and is at least
// kGyroScaleTolerance / 2, a bisection otherwise, and stops when the bracket is narrower than
// kGyroScaleTolerance: then the minimiser of (28) is within that of the returned scale — exactly the bound when
// the slope never changes sign. `common` is this one-dimensional search along S = s·I; `per-axis` minimises one
// axis at a time (cyclic coordinate descent, exact per axis) until a sweep moves no axis by more than
// kPerAxisSweepTolerance. The objective then evaluates (28) of the scaled model, ε = mean ‖ω_m − S·ω_s‖, and every
// stage — search, identifiability, intervals, model-error statement — sees the scale projected out: its
// uncertainty enters the other parameters' through the Jacobian and the profiles of the projected residuals.
// Since S = I is in the box, a fit with the scale never has a larger (28) at its parameters than without it.
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

// The stop rule of the search (header comment): the bracket of the minimiser of (28) in one scale is narrower
// than this [1]. 1e-12 is ~5000 ulp at 1 (the slope's round-off stays far below it) and 10⁻¹⁰ of the scale's
// 95 % width on the sample trials (~0.01).
constexpr double kGyroScaleTolerance = 1e-12;
// The bisections from the full box down to kGyroScaleTolerance take log2(0.2 / 1e-12) ≈ 38 steps; Newton steps
// only shorten it. A cap that no search reaches, kept against an endless loop on a non-finite slope.
constexpr int kMaxGyroScaleIterations = 100;
// per-axis: the sweeps end when no axis moved by more than this [1] (100 × the one-axis tolerance, still 10⁻⁸ of
// the scale's width: the axes are coupled only through the norm in ‖d_k‖, weakly, so the sweeps converge
// linearly and fast), at most kMaxPerAxisSweeps of them.
constexpr double kPerAxisSweepTolerance = 1e-10;
constexpr int kMaxPerAxisSweeps = 50;

// The weighted least-squares scale on the nodes (the start of the search), clamped to the box:
//   per axis a:  s_a = Σ_k w_k ω_m,a,k ω_s,a,k / Σ_k w_k ω_s,a,k²,   common:  s = Σ_k w_k ω_m,k · ω_s,k / Σ_k w_k ‖ω_s,k‖²
// a reading censored at the rail left out of both sums, a silent axis at 1; (1, 1, 1) for kOff.
Eigen::Vector3d LeastSquaresGyroScale(const ErrorNodes& nodes, const std::vector<Eigen::Vector3d>& w_s_B,
                                      GyroScaleMode mode);

// The scale that minimises (28) (header comment) for the nodes and the model's ω_s at them (same length);
// (1, 1, 1) for kOff. An axis without model motion (kSilentAxisFraction) keeps 1 in kPerAxis.
Eigen::Vector3d ProjectedGyroScale(const ErrorNodes& nodes, const std::vector<Eigen::Vector3d>& w_s_B,
                                   GyroScaleMode mode);

}  // namespace rockfit::fitting
