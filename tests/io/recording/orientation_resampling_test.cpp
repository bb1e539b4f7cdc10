#include "recording/orientation_resampling.hpp"

#include <gtest/gtest.h>

#include "recording/time_base.hpp"

namespace rockfit::io {
namespace {

constexpr double kRoundoff = 1e-12;  // rad

// Rotation about a fixed axis at a constant rate: slerp between any two samples is exact.
Eigen::Quaterniond Spin(double t) { return Eigen::Quaterniond(Eigen::AngleAxisd(2.0 * t, Eigen::Vector3d(1, 2, 2) / 3.0)); }

double AngleBetween(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) { return a.angularDistance(b); }

TEST(ResampleOrientation, InterpolatesASlowerSeriesExactlyForAConstantSpin) {
  OrientationSeries series;
  for (int k = 0; k <= 64; ++k) {
    series.t_s.push_back(k / 128.0);
    series.q_WS.push_back(Spin(k / 128.0));
  }
  const std::vector<double> target = UniformTimes(129, 256.0);
  const ResampledOrientation result = ResampleOrientation(target, series);
  EXPECT_EQ(result.first, 0u);
  ASSERT_EQ(result.q_WS.size(), 129u);
  for (std::size_t k = 0; k < target.size(); ++k) EXPECT_LT(AngleBetween(result.q_WS[k], Spin(target[k])), kRoundoff);
  EXPECT_TRUE(result.holes.empty());
}

TEST(ResampleOrientation, CoversOnlyTheSpanOfTheSeries) {
  OrientationSeries series;
  for (int k = 2; k <= 5; ++k) {
    series.t_s.push_back(k * 0.1);
    series.q_WS.push_back(Spin(k * 0.1));
  }
  const ResampledOrientation result = ResampleOrientation(UniformTimes(10, 10.0), series);
  EXPECT_EQ(result.first, 2u);
  EXPECT_EQ(result.q_WS.size(), 4u);
}

TEST(ResampleOrientation, ReportsHolesThatGyroSamplesFallInto) {
  OrientationSeries series;
  for (int k : {0, 1, 2, 6, 7, 8}) {
    series.t_s.push_back(k * 0.01);
    series.q_WS.push_back(Spin(k * 0.01));
  }
  const ResampledOrientation result = ResampleOrientation(UniformTimes(9, 100.0), series);
  ASSERT_EQ(result.holes.size(), 1u);
  EXPECT_NEAR(result.holes[0].t_s, 0.02, 1e-12);
  EXPECT_NEAR(result.holes[0].duration_s, 0.04, 1e-12);
  EXPECT_EQ(result.holes[0].samples, 3u);
  EXPECT_LT(AngleBetween(result.q_WS[4], Spin(0.04)), kRoundoff);
}

TEST(ResampleOrientation, TakesTheShortWayAcrossTheQuaternionSignFlip) {
  OrientationSeries series;
  series.t_s = {0.0, 1.0};
  series.q_WS = {Spin(0.0), Eigen::Quaterniond(-Spin(0.2).coeffs())};  // same rotation as Spin(0.2)
  const ResampledOrientation result = ResampleOrientation({0.5}, series);
  ASSERT_EQ(result.q_WS.size(), 1u);
  EXPECT_LT(AngleBetween(result.q_WS[0], Spin(0.1)), kRoundoff);
}

}  // namespace
}  // namespace rockfit::io
