// The gyro scale of a fit (gyro_scale.hpp) with its 95 % interval. The scale is a parameter of the fit like the
// others, only projected out: at the fitted (t0, α, λ's) = θ̂ it is S(θ̂), and its variance has two parts,
//
//   Var s_a = Var(s_a | θ̂) + G_a·Cov(θ)·G_aᵀ,      G_a = ∂s_a/∂θ,
//
// the first the noise at fixed θ of the least-squares scale (LeastSquaresGyroScale), taken for that of the (28)
// minimiser the fit uses (both estimate the same s; fitting/README.md), the second what the uncertainty of θ
// moves it (the two add: the marginal variance of a linear parameter in a separable least-squares problem).
// Var(s_a | θ̂) =
// V_a / D_a², D_a = Σ w_k ω_s,a,k², V_a the Newey–West long-run variance (Bartlett window of
// IntervalOptions::noise_correlation_window_s) of the score terms w_k ω_s,a,k (ω_m − S ω_s)_a,k, times the
// model-error allowance and the model-error widening factor² of the other 95 % intervals; G_a by central
// differences (CeresOptions::difference_step), Cov(θ) the linearised covariance of the 95 % level
// (UncertaintySummary::linearised_sigma_95 and the correlation of the same matrix) times the widening factor²,
// over the parameters whose final 95 % interval is closed. Not the final interval ends: t0's floor and the
// hull widen them unequally, which breaks the cancellation along the t0–α ridge that the correlation expects.
// The 95 % interval is s_a ± 1.96·√Var s_a.
#pragma once

#include <array>
#include <string>

#include <Eigen/Core>

#include "rockfit/fitting/fit_options.hpp"
#include "rockfit/fitting/gyro_scale.hpp"
#include "rockfit/fitting/objective.hpp"
#include "rockfit/fitting/uncertainty.hpp"

namespace rockfit::fitting {

struct GyroScaleEstimate {
  GyroScaleMode mode = GyroScaleMode::kOff;
  bool available = false;  // estimated at a feasible fit
  Eigen::Vector3d value = Eigen::Vector3d::Ones();  // s_x, s_y, s_z [1] (three equal values for kCommon)
  // Per body axis; NaN ends where the axis carries no model motion (its scale stays 1) or nothing was estimated.
  std::array<Interval, 3> interval_95{};
  // Whether the data fix the axis's scale: its 95 % interval is closed and narrower than half the admissible
  // range [1 − kMaxGyroScaleError, 1 + kMaxGyroScaleError] (as IntervalOptions::undetermined_range_fraction
  // judges the other parameters). The lateral axes of a nearly planar rocking are usually not determined.
  std::array<bool, 3> determined{};
  Eigen::Vector3d half_width_noise = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  Eigen::Vector3d half_width_parameters = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
};

// The estimate at `fitted` of an objective that projects the scale out (objective.options().gyro_scale), with
// the other parameters' uncertainty in `u` (which are closed at 95 %, their linearised σ's and correlation) and
// the model-error widening factor their intervals carry. Returns an
// estimate with available = false for kOff or where the model fails at `fitted`.
GyroScaleEstimate EstimateGyroScale(const Objective& objective, const ParameterSet& fitted, const UncertaintySummary& u,
                                    double widening_factor, const FitOptions& options);

// {"mode": …, "available": …, "value": [s_x, s_y, s_z], "interval_95": [[lo, hi] or null × 3],
// "determined": [bool × 3], "half_width_noise": [× 3], "half_width_parameters": [× 3]} (the two parts of the
// 95 % half-width, which add in quadrature; null where not estimated); null when the mode is off.
std::string GyroScaleJson(const GyroScaleEstimate& e);
// One line for the fit's table.
std::string GyroScaleText(const GyroScaleEstimate& e);

}  // namespace rockfit::fitting
