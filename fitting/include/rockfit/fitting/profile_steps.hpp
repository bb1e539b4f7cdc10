// Where the profile of one parameter places its points (uncertainty.hpp, `thorough`; fitting/README.md,
// "Intervals"): aimed at the 95 % crossing of the signed root instead of on a fixed grid, and the other
// parameters started on the linearised ridge.
//
// Offsets are in units of the parameter's profile step (its linearised σ_j), ρ = √((S − S_centre)/(κ_j·s²)) the
// signed root at a point. Where S is quadratic along the ridge, ρ grows linearly with the offset, so a point
// aimed a little beyond z = 1.96 brackets the crossing at once and the linear interpolation between the
// centre and it is exact; where it is not, the secant of ρ through the last two points aims the next one.
#pragma once

#include <Eigen/Core>

namespace rockfit::fitting {

// One profile point: offset from the centre [σ_j] and the signed root there.
struct ProfileStepPoint {
  double offset = 0.0;
  double rho = 0.0;
};

// The aim of the steps: the ρ a new point aims at and the range of its offset as multiples of the last one.
struct ProfileAim {
  double target_rho = 2.2;
  double min_growth = 1.25;
  double max_growth = 2.0;
};

// The offset of the next point outwards, after `last` (with `before` the point inside it, or the centre
// {0, 0}): the secant of ρ through the two set to aim.target_rho, clamped to [min_growth, max_growth]·last.offset;
// aim.max_growth·last.offset where ρ did not rise between them.
double NextProfileOffset(const ProfileStepPoint& before, const ProfileStepPoint& last, const ProfileAim& aim);

// The offset of a point inside a bracket [inner, outer] (inner.rho < z < outer.rho) aimed at `target_rho`
// by the secant through the two; inside the open bracket by at least a tenth of its width on each side.
double RefineProfileOffset(const ProfileStepPoint& inner, const ProfileStepPoint& outer, double target_rho);

// The slope of the linearised ridge of a profile: how the other parameters move per unit of parameter j
// when they are re-fitted, dθ_o/dθ_j = M_oj / M_jj for M = (JᵀJ)⁻¹ (the conditional mean of a Gaussian); a
// vector of zeros when M_jj is not positive and finite.
Eigen::VectorXd RidgeSlope(const Eigen::MatrixXd& inverse_normal_matrix, Eigen::Index j);

}  // namespace rockfit::fitting
