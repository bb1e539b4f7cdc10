// A release rolled off the rocking plane (rolled_release.hpp): its attitude and pivot against the rotation the
// other-physics generator builds (R_WB = Ry(−α)·Rx(β) for the edge V1V2), the first motion against Euler's
// equations about the pivot at rest, the mirror symmetry of ±β, the limit β → 0 against the release on the edge,
// and the roll's bounds.
#include "rockfit/core/rolled_release.hpp"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/core/simulator.hpp"

namespace rockfit::core {
namespace {

// A granite block of the other-physics studies (half-extents b1, b2, h [m]).
Block StudyBlock() { return Block::FromDensity(0.05000453, 0.035, 0.2, 2692.0); }

ModelParameters Rolled(double alpha_rad, double roll_rad) {
  ModelParameters p;
  p.alpha_rad = alpha_rad;
  p.release_roll_rad = roll_rad;
  p.lambda = 1.0;
  p.lambda_lat = 0.3;
  p.lambda_lon = 0.9;
  return p;
}

TEST(RolledRelease, AttitudeIsTheTiltAboutTheEdgeThenTheRollAboutX) {
  const Block block = StudyBlock();
  for (double roll : {0.01, -0.004}) {
    const RolledRelease r = MakeRolledRelease(block, 1, 2, 0.2, roll);
    const Eigen::Quaterniond expected(Eigen::AngleAxisd(-0.2, Eigen::Vector3d::UnitY()) *
                                      Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()));
    EXPECT_LT(r.q_WB.angularDistance(expected), 1e-14) << roll;
    // β > 0 lowers the −y corner V1, β < 0 the +y corner V2.
    EXPECT_EQ(r.pivot_vertex, roll > 0 ? 1 : 2) << roll;
  }
}

TEST(RolledRelease, RejectsAZeroOrNonFiniteRollAndSimulateRejectsARollOfAQuarterTurn) {
  const Block block = StudyBlock();
  EXPECT_THROW(MakeRolledRelease(block, 1, 2, 0.2, 0.0), InvalidArgument);
  EXPECT_THROW(MakeRolledRelease(block, 1, 2, 0.2, std::nan("")), InvalidArgument);
  EXPECT_THROW(MakeRolledRelease(block, 1, 3, 0.2, 0.01), InvalidArgument);  // V1, V3 are not neighbours
  EXPECT_THROW(Simulate(block, Rolled(0.2, M_PI / 4.0), SimulationOptions{}), InvalidArgument);
}

TEST(RolledRelease, FirstMotionFollowsEulersEquationsAboutThePivotAtRest) {
  // At rest on V1, ω̇ = J_V⁻¹ (p_VC × (−m g e_z)) with J_V the inertia about V1 (parallel axes), all in B; ω̈ = 0
  // at rest, so ω(t) = ω̇ t up to O(t³).
  const Block block = StudyBlock();
  const double alpha = 0.2, roll = 0.01;
  const Eigen::Quaterniond q_WB(Eigen::AngleAxisd(-alpha, Eigen::Vector3d::UnitY()) *
                                Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()));
  const double m = block.mass(), b1 = block.b1(), b2 = block.b2(), h = block.h();
  const Eigen::Vector3d p_VC_B(b1, b2, h);  // from V1 = (−b1, −b2, 0) to the centre (0, 0, h)
  const Eigen::Matrix3d J_C =
      Eigen::Vector3d(m / 3 * (b2 * b2 + h * h), m / 3 * (b1 * b1 + h * h), m / 3 * (b1 * b1 + b2 * b2)).asDiagonal();
  const Eigen::Matrix3d J_V = J_C + m * (p_VC_B.squaredNorm() * Eigen::Matrix3d::Identity() - p_VC_B * p_VC_B.transpose());
  const Eigen::Vector3d gravity_B = q_WB.conjugate() * Eigen::Vector3d(0, 0, -m * kStandardGravity);
  const Eigen::Vector3d w_dot_B = J_V.inverse() * p_VC_B.cross(gravity_B);

  SimulationOptions options;
  constexpr double kEarly_s = 1e-3;  // long before the corner V2 lands (≈ 40 ms for 0.01 rad)
  options.sample_times_s = {kEarly_s};
  const Trajectory tr = Simulate(block, Rolled(alpha, roll), options);
  ASSERT_EQ(tr.w_B.size(), 1u) << tr.message;
  EXPECT_EQ(tr.mode[0].kind, ModeKind::kVertex);
  EXPECT_EQ(tr.mode[0].contact.first, 1);
  // O(t³) over ω̇ t: (K t)² with K² ≈ g/R ≈ 50 s⁻², so 1e-4 relative is ample at 1 ms.
  constexpr double kRelativeTol = 1e-4;
  EXPECT_LT((tr.w_B[0] - w_dot_B * kEarly_s).norm(), kRelativeTol * (w_dot_B * kEarly_s).norm())
      << tr.w_B[0].transpose() << " vs " << (w_dot_B * kEarly_s).transpose();
}

TEST(RolledRelease, OppositeRollsMirrorTheFallAcrossTheRockingPlane) {
  // Reflecting y → −y maps ω = (ωx, ωy, ωz) to (−ωx, ωy, −ωz); before the first impact no impact law enters.
  const Block block = StudyBlock();
  SimulationOptions options;
  const Trajectory plus = Simulate(block, Rolled(0.2, 0.005), options);
  const Trajectory minus = Simulate(block, Rolled(0.2, -0.005), options);
  ASSERT_FALSE(plus.impacts.empty());
  const double first_impact_s = plus.impacts.front().t_s;
  ASSERT_NEAR(minus.impacts.front().t_s, first_impact_s, 1e-9);
  int compared = 0;
  constexpr double kMirrorTol_rad_s = 1e-9;  // two integrations of mirrored states, tolerances 1e-12
  for (std::size_t k = 0; k < plus.t_s.size() && plus.t_s[k] < first_impact_s; ++k) {
    EXPECT_NEAR(minus.w_B[k].x(), -plus.w_B[k].x(), kMirrorTol_rad_s);
    EXPECT_NEAR(minus.w_B[k].y(), plus.w_B[k].y(), kMirrorTol_rad_s);
    EXPECT_NEAR(minus.w_B[k].z(), -plus.w_B[k].z(), kMirrorTol_rad_s);
    ++compared;
  }
  EXPECT_GT(compared, 3);
  EXPECT_GT(std::abs(plus.w_B[compared - 1].x()), 1e-3);  // the premise: the roll rocks the block about x
}

// The largest |Δω| [rad/s] between the release rolled by roll_rad and the release on the edge, over the samples
// before the edge release's first landing.
double LargestDifferenceFromTheEdgeRelease(double roll_rad, double* largest_rad_s) {
  const Block block = StudyBlock();
  SimulationOptions options;
  const Trajectory edge = Simulate(block, Rolled(0.2, 0.0), options);
  const Trajectory rolled = Simulate(block, Rolled(0.2, roll_rad), options);
  const double first_landing_s = edge.impacts.empty() ? 0.0 : edge.impacts.front().t_s;
  double largest_difference_rad_s = 0.0;
  *largest_rad_s = 0.0;
  for (std::size_t k = 0; k < std::min(edge.t_s.size(), rolled.t_s.size()) && edge.t_s[k] < first_landing_s; ++k) {
    *largest_rad_s = std::max(*largest_rad_s, edge.w_B[k].norm());
    largest_difference_rad_s = std::max(largest_difference_rad_s, (edge.w_B[k] - rolled.w_B[k]).norm());
  }
  return largest_difference_rad_s;
}

TEST(RolledRelease, ATinyRollApproachesTheReleaseOnTheEdge) {
  double largest_rad_s = 0.0;
  double previous = LargestDifferenceFromTheEdgeRelease(1e-4, &largest_rad_s);
  EXPECT_GT(largest_rad_s, 0.5);  // the premise: the fall reaches 0.5 rad/s before the first landing
  for (double roll : {1e-5, 1e-6, 1e-7, 1e-8}) {
    const double difference = LargestDifferenceFromTheEdgeRelease(roll, &largest_rad_s);
    EXPECT_LT(difference, previous) << "roll " << roll;  // the rolled release tends to the edge release
    previous = difference;
  }
  // β = 1e-8 (10⁻¹⁰ m of drop onto the edge): a hundredth of a gyro's noise (≈ 1e-3 rad/s).
  constexpr double kTinyRollEffect_rad_s = 1e-5;
  EXPECT_LT(previous, kTinyRollEffect_rad_s);
}

}  // namespace
}  // namespace rockfit::core
