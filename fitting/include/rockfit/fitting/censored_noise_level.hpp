// The residual noise level of a fit with clipped gyro samples: the maximum-likelihood σ of a normal model in
// which a censored component (an axis at the gyro's rail, gyro_clipping.hpp) contributes the probability that
// the measurement lies beyond the rail — the Tobit likelihood (Tobin 1958; fitting/README.md, "Clipped gyro
// samples") — instead of being left out of the count.
//
// With r_i the weighted residuals of the plain components (S = Σ r_i²) and m_c = √w·s·(ω_s − ω_m) the weighted
// margin of a censored component (s the sense of the rail; m_c > 0 where the model is beyond the rail, what the
// recording allows), the log-likelihood in θ = 1/σ is, with the degrees of freedom ν in place of the number of
// plain components (the usual correction for the fitted parameters),
//
//   L(θ) = ν·log θ − θ²·S/2 + Σ_c log Φ(θ·m_c),
//
// concave in θ (log Φ is concave and θ·m_c linear), so the stationary point
//
//   L′(θ) = ν/θ − θ·S + Σ_c m_c·λ(θ·m_c) = 0,   λ(z) = φ(z)/Φ(z) (the inverse Mills ratio),
//
// is unique; it is found by Newton steps kept inside a bracket of the sign change (bisection where a step
// leaves it). Without censored components it is σ² = S/ν, today's estimate, returned by that very expression.
// A component far beyond the rail adds nothing (m·λ(θm) → 0), as a satisfied one counted before; one far short
// of it adds its margin² to S and takes a degree of freedom away (−log Φ(z) ≈ z²/2 + log|z|), more than a plain
// residual of that size would. In between (0 < m of the order of σ) it lowers σ: the censored observation is
// likelier the smaller the noise. So the censored σ is *below* the uncensored count's wherever the model is at or
// beyond the rail on every clipped node: the likelihood cannot see the misfit the rail hides.
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "rockfit/fitting/objective.hpp"
#include "rockfit/fitting/parameters.hpp"
#include "rockfit/fitting/trajectory_error.hpp"

namespace rockfit::fitting {

// The residuals of one fit split for the censored likelihood.
struct CensoredResiduals {
  double observed_sum_sq = 0.0;      // S: Σ w_k (ω_m − ω_s)_a² over the plain components of the nodes with weight
  std::size_t observed_components = 0;
  std::vector<double> censored_margins;  // m_c, one per censored component of a node with weight
  // The count and sum of squares of the noise level as it was before the censored likelihood: every component
  // of a node with weight but the censored ones the model satisfies, with NodeMisfit's residual.
  double misfit_sum_sq = 0.0;
  std::size_t misfit_components = 0;
};

// Splits the misfit of the nodes with weight (the model's ω_s at the nodes, same length).
CensoredResiduals CollectCensoredResiduals(const ErrorNodes& nodes, const std::vector<Eigen::Vector3d>& w_s_B);

// The inverse Mills ratio φ(z)/Φ(z), accurate for every finite z (a continued fraction where Φ(z) underflows).
double InverseMillsRatio(double z);

// The maximum-likelihood variance σ² above for S = observed_sum_sq, ν = degrees_of_freedom (> 0) and the
// censored margins; exactly observed_sum_sq / degrees_of_freedom when there are none. NaN when ν ≤ 0.
double CensoredNoiseVariance(double observed_sum_sq, double degrees_of_freedom, const std::vector<double>& margins);

// σ² of the censored likelihood over the noise level before it, Σ NodeMisfit² / (3·nodes − satisfied − p), for
// `free_parameters` = p fitted parameters; exactly 1 without censored components (and where either is not
// defined), so that the intervals of a recording without a rail are unchanged to the last digit.
double CensoredNoiseFactor(const ErrorNodes& nodes, const std::vector<Eigen::Vector3d>& w_s_B,
                           std::size_t free_parameters);
// The same at `at` of `objective`: 1 without a model run when the signal has no censored axis or the model fails.
double CensoredNoiseFactorAt(const Objective& objective, const ParameterSet& at, std::size_t free_parameters);

}  // namespace rockfit::fitting
