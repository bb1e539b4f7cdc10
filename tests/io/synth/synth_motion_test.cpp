// From a simulated trajectory to the true motion of a recording: rest before the release, the trajectory's
// samples in order, rest after the end, pivots and breaks — on a hand-made trajectory with known values.
#include "rockfit/io/synth_motion.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "rockfit/core/errors.hpp"

namespace rockfit::io {
namespace {

constexpr double kRate = 256.0;

core::Mode EdgeMode(int i, int j) {
  core::Mode m;
  m.kind = core::ModeKind::kEdge;
  m.contact = core::Contact{i, j};
  return m;
}
core::Mode VertexMode(int k) {
  core::Mode m;
  m.kind = core::ModeKind::kVertex;
  m.contact = core::Contact{k, 0};
  return m;
}

// A trajectory as Synthesize requests it: τ = 0, then τ_n = n/f − t0 for n ≥ release while it lasts.
core::Trajectory HandMadeTrajectory(double t0, std::size_t release, std::size_t count) {
  core::Trajectory t;
  const auto push = [&t](double tau, const core::Mode& mode) {
    t.t_s.push_back(tau);
    t.w_B.emplace_back(0.1 * tau, 1.0 + tau, -0.2 * tau);
    t.q_WB.push_back(Eigen::Quaterniond(Eigen::AngleAxisd(-0.2 + tau, Eigen::Vector3d::UnitY())));
    t.mode.push_back(mode);
  };
  push(0.0, EdgeMode(1, 2));
  for (std::size_t n = release; n < release + count; ++n) {
    const double tau = static_cast<double>(n) / kRate - t0;
    push(tau, tau < 0.05 ? EdgeMode(1, 2) : VertexMode(3));
  }
  core::ImpactRecord facet;
  facet.t_s = 0.05;
  facet.kind = core::ImpactKind::kFacet;
  facet.w_minus_B = Eigen::Vector3d(0.0, 1.5, 0.0);
  facet.w_plus_B = Eigen::Vector3d(0.1, 1.2, 0.0);
  t.impacts.push_back(facet);
  t.t_end_s = t.t_s.back();
  t.end_reason = core::EndReason::kTMax;
  return t;
}

TEST(SynthMotion, MotionRestsBeforeTheReleaseFollowsTheTrajectoryAndRestsAfterItsEnd) {
  const core::Block block = core::Block::FromDensity(0.05, 0.03, 0.2, 2692.0);
  const double t0 = 0.3;
  const std::size_t release = 77;  // ceil(0.3·256) = 77: τ = 77/256 − 0.3 > 0
  const std::size_t samples = 200;
  const core::Trajectory trajectory = HandMadeTrajectory(t0, release, 60);
  const BlockMotion m = BlockMotionFromTrajectory(block, trajectory, t0, kRate, samples, release, 9.81);
  ASSERT_EQ(m.size(), samples);
  for (std::size_t n = 0; n < release; ++n) {
    EXPECT_EQ(m.w_B[n], Eigen::Vector3d::Zero()) << n;
    EXPECT_TRUE(m.q_WB[n].isApprox(trajectory.q_WB[0], 1e-15)) << n;
    EXPECT_TRUE(m.p_BK_B[n].isApprox(Eigen::Vector3d(-0.05, 0.0, 0.0), 1e-15)) << "edge V1V2 midpoint";
  }
  for (std::size_t n = release; n < release + 60; ++n) {
    const std::size_t k = 1 + (n - release);
    EXPECT_EQ(m.w_B[n], trajectory.w_B[k]) << n;
    const double tau = static_cast<double>(n) / kRate - t0;
    EXPECT_EQ(m.p_BK_B[n], tau < 0.05 ? Eigen::Vector3d(-0.05, 0.0, 0.0) : block.p_BV_B(3)) << n;
  }
  for (std::size_t n = release + 60; n < samples; ++n) {
    EXPECT_EQ(m.w_B[n], Eigen::Vector3d::Zero()) << n;
    EXPECT_TRUE(m.q_WB[n].isApprox(trajectory.q_WB.back(), 1e-15)) << n;
  }
  ASSERT_EQ(m.impacts.size(), 1u);
  EXPECT_DOUBLE_EQ(m.impacts[0].t_s, t0 + 0.05);
  EXPECT_EQ(m.impacts[0].w_plus_B, trajectory.impacts[0].w_plus_B);
  EXPECT_EQ(m.breaks_s, (std::vector<double>{t0, t0 + 0.05, t0 + trajectory.t_end_s}));
}

TEST(SynthMotion, ReleaseExactlyOnASampleSharesTheTrajectoryFirstSample) {
  const core::Block block = core::Block::FromDensity(0.05, 0.03, 0.2, 2692.0);
  const double t0 = 0.25;  // = 64/256: τ of sample 64 is exactly 0
  const std::size_t release = 64;
  core::Trajectory trajectory = HandMadeTrajectory(t0, release + 1, 10);  // τ = 0 then samples 65 …
  const BlockMotion m = BlockMotionFromTrajectory(block, trajectory, t0, kRate, 100, release, 9.81);
  EXPECT_EQ(m.w_B[release], trajectory.w_B[0]);
  EXPECT_EQ(m.w_B[release + 1], trajectory.w_B[1]);
}

TEST(SynthMotion, TrajectorySampledAtOtherTimesIsRejected) {
  const core::Block block = core::Block::FromDensity(0.05, 0.03, 0.2, 2692.0);
  core::Trajectory trajectory = HandMadeTrajectory(0.3, 77, 10);
  trajectory.t_s[3] += 1e-6;
  EXPECT_THROW(BlockMotionFromTrajectory(block, trajectory, 0.3, kRate, 100, 77, 9.81), NumericalFailure);
}

}  // namespace
}  // namespace rockfit::io
