// Output sampling of the simulator: sample times, the cut-off at the last time, and the cheap mode.
#include "detail/trajectory_sampler.hpp"

#include <gtest/gtest.h>

namespace rockfit::core::detail {
namespace {

Mode EdgeMode12() {
  Mode m;
  m.kind = ModeKind::kEdge;
  m.contact = Contact::Edge(1, 2);
  return m;
}

TEST(TrajectorySampler, SamplesAtKOverRateUpToTheLastTime) {
  SimulationOptions options;
  options.rate_hz = 4.0;
  Trajectory out;
  TrajectorySampler sampler(options, 1.0, &out);
  std::vector<double> times;
  while (sampler.pending()) {
    times.push_back(sampler.next_time());
    sampler.Emit(EdgeMode12(), Eigen::Vector3d(0.0, 1.0, 0.0), [] { return Eigen::Quaterniond::Identity(); });
  }
  EXPECT_EQ(times, (std::vector<double>{0.0, 0.25, 0.5, 0.75, 1.0}));
  ASSERT_EQ(out.t_s.size(), 5u);
  EXPECT_EQ(out.q_WB.size(), 5u);
  EXPECT_EQ(out.euler_zyx.size(), 5u);
  EXPECT_EQ(out.mode[2].ToString(), "V1V2");
}

TEST(TrajectorySampler, GivenTimesBeyondTheLastAreDropped) {
  SimulationOptions options;
  options.sample_times_s = {-0.1, 0.3, 0.7, 1.2};
  Trajectory out;
  TrajectorySampler sampler(options, 1.0, &out);
  std::vector<double> times;
  while (sampler.pending()) {
    times.push_back(sampler.next_time());
    sampler.Emit(EdgeMode12(), Eigen::Vector3d::Zero(), [] { return Eigen::Quaterniond::Identity(); });
  }
  EXPECT_EQ(times, (std::vector<double>{-0.1, 0.3, 0.7}));
}

TEST(TrajectorySampler, WithoutAttitudeTheAttitudeIsNeverComputed) {
  SimulationOptions options;
  options.rate_hz = 10.0;
  options.sample_attitude = false;
  Trajectory out;
  TrajectorySampler sampler(options, 0.5, &out);
  int calls = 0;
  while (sampler.pending()) {
    sampler.Emit(EdgeMode12(), Eigen::Vector3d::Zero(), [&calls] {
      ++calls;
      return Eigen::Quaterniond::Identity();
    });
  }
  EXPECT_EQ(calls, 0);
  EXPECT_EQ(out.t_s.size(), 6u);
  EXPECT_TRUE(out.q_WB.empty());
}

TEST(TrajectorySampler, QuaternionsAreCanonicalAndEulerAnglesFollowThem) {
  SimulationOptions options;
  options.rate_hz = 1.0;
  Trajectory out;
  TrajectorySampler sampler(options, 0.0, &out);
  const Eigen::Quaterniond q(Eigen::AngleAxisd(-0.2, Eigen::Vector3d::UnitY()));
  sampler.Emit(EdgeMode12(), Eigen::Vector3d::Zero(), [&q] { return Eigen::Quaterniond(-q.coeffs()); });
  ASSERT_EQ(out.q_WB.size(), 1u);
  EXPECT_GE(out.q_WB[0].w(), 0.0);
  EXPECT_NEAR(out.euler_zyx[0][1], -0.2, 1e-15);
}

}  // namespace
}  // namespace rockfit::core::detail
