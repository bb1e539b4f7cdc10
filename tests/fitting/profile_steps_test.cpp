// Where the aimed profile places its points (profile_steps.hpp): the secant lands on the target where the
// signed root is linear in the offset (a quadratic profile), stays within its growth limits otherwise, a
// refinement stays inside its bracket, and the ridge slope is the Gaussian conditional mean's.
#include "rockfit/fitting/profile_steps.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/fit_options.hpp"

namespace rockfit::fitting {
namespace {

constexpr double kTol = 1e-12;  // closed forms evaluated in double precision

TEST(NextProfileOffset, LandsOnTheTargetWhereRhoIsLinearInTheOffset) {
  // ρ = 0.7·offset (a quadratic profile 1.43 times wider than the linearised σ).
  const ProfileAim aim;
  const ProfileStepPoint centre{0.0, 0.0}, first{2.2, 0.7 * 2.2};
  const double next = NextProfileOffset(centre, first, aim);
  EXPECT_NEAR(next, aim.target_rho / 0.7, kTol);
  // From two points off the centre as well: ρ = 0.5 + 0.6·offset.
  const ProfileStepPoint a{1.0, 0.5 + 0.6 * 1.0}, b{2.0, 0.5 + 0.6 * 2.0};
  EXPECT_NEAR(NextProfileOffset(a, b, aim), (aim.target_rho - 0.5) / 0.6, kTol);
}

TEST(NextProfileOffset, StaysWithinItsGrowthLimits) {
  const ProfileAim aim;
  const ProfileStepPoint centre{0.0, 0.0};
  // A profile ten times wider than linearised: the secant says 22, the step at most doubles.
  EXPECT_NEAR(NextProfileOffset(centre, {2.2, 0.22}, aim), aim.max_growth * 2.2, kTol);
  // Just below the target: at least min_growth further out.
  EXPECT_NEAR(NextProfileOffset(centre, {2.2, 2.19}, aim), aim.min_growth * 2.2, kTol);
  // ρ did not rise (a flat or falling profile): the largest step.
  EXPECT_NEAR(NextProfileOffset({1.0, 0.5}, {2.0, 0.4}, aim), aim.max_growth * 2.0, kTol);
}

TEST(RefineProfileOffset, LandsOnTheTargetInsideALinearBracket) {
  // ρ = 3·offset between 0 and 2.2 (a profile three times narrower than linearised): target 2.2 at 0.733.
  EXPECT_NEAR(RefineProfileOffset({0.0, 0.0}, {2.2, 6.6}, 2.2), 2.2 / 3.0, kTol);
}

TEST(RefineProfileOffset, StaysInsideTheBracket) {
  const ProfileStepPoint inner{1.0, 1.0}, outer{3.0, 50.0};
  const double x = RefineProfileOffset(inner, outer, 2.2);
  EXPECT_GE(x, 1.0 + 0.1 * 2.0 - kTol);
  EXPECT_LE(x, 3.0 - 0.1 * 2.0 + kTol);
  // An end where the model failed (ρ infinite): the middle.
  EXPECT_NEAR(RefineProfileOffset(inner, {3.0, std::numeric_limits<double>::infinity()}, 2.2), 2.0, kTol);
}

TEST(RidgeSlope, IsTheConditionalMeanOfAGaussian) {
  // Covariance of (x, y) with σ_x = 2, σ_y = 0.5, correlation −0.9: E[y | x] moves by ρ·σ_y/σ_x per unit of x.
  const double sx = 2.0, sy = 0.5, rho = -0.9;
  Eigen::MatrixXd m(2, 2);
  m << sx * sx, rho * sx * sy, rho * sx * sy, sy * sy;
  const Eigen::VectorXd slope = RidgeSlope(m, 0);
  EXPECT_EQ(slope[0], 0.0);
  EXPECT_NEAR(slope[1], rho * sy / sx, kTol);
  const Eigen::VectorXd back = RidgeSlope(m, 1);
  EXPECT_NEAR(back[0], rho * sx / sy, kTol);
}

TEST(RidgeSlope, IsZeroWithoutAPositiveVariance) {
  Eigen::MatrixXd m = Eigen::MatrixXd::Identity(3, 3);
  m(1, 1) = 0.0;
  EXPECT_TRUE(RidgeSlope(m, 1).isZero());
  m(1, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(RidgeSlope(m, 1).isZero());
}

// The aimed points must pass the 95 % crossing (z = 1.96) to bracket it, and a refinement threshold below the
// aim would refine every point.
TEST(IntervalOptions, RejectsAnAimThatCannotBracketTheCrossing) {
  IntervalOptions options;
  options.profile_aim_rho = 1.9;
  EXPECT_THROW(options.Validate(), InvalidArgument);
  options.profile_aim_rho = 2.2;
  options.profile_refine_above_rho = 2.0;
  EXPECT_THROW(options.Validate(), InvalidArgument);
  options.profile_refine_above_rho = 3.0;
  EXPECT_NO_THROW(options.Validate());
}


// IntervalOptions::profile_refit and its iteration counts: an unknown refit or no iterations is refused.
TEST(IntervalOptions, RejectsAnUnknownRefitAndNoIterations) {
  IntervalOptions options;
  options.profile_refit = static_cast<ProfileRefit>(7);
  EXPECT_THROW(options.Validate(), InvalidArgument);
  options = IntervalOptions{};
  options.refit_iterations = 0;
  EXPECT_THROW(options.Validate(), InvalidArgument);
  options = IntervalOptions{};
  options.centre_iterations = -1;
  EXPECT_THROW(options.Validate(), InvalidArgument);
  options = IntervalOptions{};
  options.profile_refit = ProfileRefit::kExact;
  EXPECT_NO_THROW(options.Validate());
  ProfileRefit parsed = ProfileRefit::kNelderMead;
  ASSERT_TRUE(FromString(ToString(ProfileRefit::kExact), &parsed));
  EXPECT_EQ(parsed, ProfileRefit::kExact);
  EXPECT_FALSE(FromString("gauss-newton", &parsed));
}

}  // namespace
}  // namespace rockfit::fitting
