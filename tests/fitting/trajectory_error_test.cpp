// The error (28) against closed-form integrals of simple signals, and its defining properties.
#include "rockfit/fitting/trajectory_error.hpp"

#include <cmath>
#include <functional>
#include <numeric>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::fitting {
namespace {

// Round-off of sums over a few hundred samples [rad/s].
constexpr double kSumTolerance = 1e-12;

MeasuredSignal UniformSignal(double rate_hz, std::size_t n, const std::function<Eigen::Vector3d(double)>& w) {
  MeasuredSignal s;
  for (std::size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) / rate_hz;
    s.t_s.push_back(t);
    s.w_B.push_back(w(t));
  }
  return s;
}

std::vector<Eigen::Vector3d> Zeros(std::size_t n) { return std::vector<Eigen::Vector3d>(n, Eigen::Vector3d::Zero()); }

TEST(TrajectoryError, ConstantDifferenceGivesItsNorm) {
  const Eigen::Vector3d c(0.3, -0.4, 1.2);  // ‖c‖ = 1.3
  const MeasuredSignal s = UniformSignal(256.0, 300, [&](double) { return c; });
  ErrorNodes nodes;
  ASSERT_TRUE(BuildErrorNodes(s, 0.0123, 1.0, &nodes));
  EXPECT_NEAR(TrajectoryError(nodes, Zeros(nodes.size())), 1.3, kSumTolerance);
}

TEST(TrajectoryError, LinearSignalIsIntegratedExactlyIncludingTheFractionalEnds) {
  // ω_m = (a t, 0, 0), ω_s = 0, t > 0: ε = a (t0 + t_end) / 2; the trapezoid rule is exact for linear data.
  const double a = 2.5;
  const MeasuredSignal s = UniformSignal(100.0, 200, [&](double t) { return Eigen::Vector3d(a * t, 0, 0); });
  for (double t0 : {0.0, 0.013, 0.5, 0.555}) {
    for (double t_end : {1.0, 1.234, 1.99}) {
      ErrorNodes nodes;
      ASSERT_TRUE(BuildErrorNodes(s, t0, t_end, &nodes));
      EXPECT_NEAR(TrajectoryError(nodes, Zeros(nodes.size())), a * (t0 + t_end) / 2.0, kSumTolerance)
          << "t0 " << t0 << " t_end " << t_end;
    }
  }
}

TEST(TrajectoryError, NodesStartAtReleaseAndWeightsSumToTheWindow) {
  const MeasuredSignal s = UniformSignal(256.0, 400, [](double t) { return Eigen::Vector3d(t, 2 * t, 0); });
  ErrorNodes nodes;
  ASSERT_TRUE(BuildErrorNodes(s, 0.1001, 1.2, &nodes));
  EXPECT_EQ(nodes.t_after_release_s.front(), 0.0);
  EXPECT_DOUBLE_EQ(nodes.t_s.front(), 0.1001);
  EXPECT_DOUBLE_EQ(nodes.t_s.back(), 1.2);
  EXPECT_NEAR(std::accumulate(nodes.weight_s.begin(), nodes.weight_s.end(), 0.0), 1.2 - 0.1001, kSumTolerance);
  // Interior nodes are exactly the samples inside the window; the model is queried at sample time − t0.
  for (std::size_t i = 1; i + 1 < nodes.size(); ++i) {
    EXPECT_EQ(nodes.t_s[i], s.t_s[nodes.first_sample + i - 1]);
    EXPECT_EQ(nodes.t_after_release_s[i], nodes.t_s[i] - 0.1001);
  }
  // The measured value at t0 is the linear interpolant.
  EXPECT_NEAR(nodes.w_m_B[0].x(), 0.1001, 1e-15);
}

TEST(TrajectoryError, IsContinuousWhenT0CrossesASampleTime) {
  // A non-linear measured signal and a model that depends on the time after release.
  const MeasuredSignal s =
      UniformSignal(256.0, 400, [](double t) { return Eigen::Vector3d(std::sin(7 * t), std::cos(3 * t), t * t); });
  auto epsilon = [&](double t0) {
    ErrorNodes nodes;
    EXPECT_TRUE(BuildErrorNodes(s, t0, 1.3, &nodes));
    std::vector<Eigen::Vector3d> w_s;
    for (double tau : nodes.t_after_release_s) w_s.emplace_back(0.5 * tau, std::sin(tau), 0.0);
    return TrajectoryError(nodes, w_s);
  };
  const double t_k = s.t_s[77];
  const double delta = 1e-10;  // s
  // Both one-sided limits agree to first order in delta (the derivative is O(1)).
  EXPECT_NEAR(epsilon(t_k - delta), epsilon(t_k), 1e-8);
  EXPECT_NEAR(epsilon(t_k + delta), epsilon(t_k), 1e-8);
}

TEST(TrajectoryError, RejectsWindowsOutsideTheRecording) {
  const MeasuredSignal s = UniformSignal(10.0, 11, [](double) { return Eigen::Vector3d::Zero(); });
  ErrorNodes nodes;
  EXPECT_FALSE(BuildErrorNodes(s, -0.1, 0.5, &nodes));
  EXPECT_FALSE(BuildErrorNodes(s, 0.5, 1.1, &nodes));
  EXPECT_FALSE(BuildErrorNodes(s, 0.5, 0.5, &nodes));
  EXPECT_TRUE(BuildErrorNodes(s, 0.0, 1.0, &nodes));
  EXPECT_EQ(nodes.size(), 11u);  // both ends are samples: no duplicate node
}

TEST(TrajectoryError, ExcludedSamplesLeaveNoTraceAndTheMeanIsOverTheTimeLeft) {
  // ω_m − ω_s = c everywhere except a block of samples (and the end nodes' neighbours) that hold 100·c and are
  // excluded: ε must still be ‖c‖ exactly, and the excluded weight is what the weights no longer cover.
  const Eigen::Vector3d c(0.3, -0.4, 1.2);  // ‖c‖ = 1.3
  MeasuredSignal s = UniformSignal(256.0, 300, [&](double) { return c; });
  s.excluded.assign(s.size(), false);
  for (std::size_t k : {0u, 1u, 40u, 41u, 42u, 43u, 100u, 255u, 256u}) {
    s.w_B[k] = 100.0 * c;
    s.excluded[k] = true;
  }
  ErrorNodes nodes;
  ASSERT_TRUE(BuildErrorNodes(s, 0.5 / 256.0, 255.5 / 256.0, &nodes));  // both ends interpolate an excluded sample
  EXPECT_NEAR(TrajectoryError(nodes, Zeros(nodes.size())), 1.3, kSumTolerance);
  const double weights = std::accumulate(nodes.weight_s.begin(), nodes.weight_s.end(), 0.0);
  EXPECT_NEAR(weights + nodes.excluded_weight_s, nodes.duration_s(), kSumTolerance);
  EXPECT_EQ(nodes.num_excluded, 9u);  // the two end nodes and interior samples 1, 40–43, 100, 255
}

TEST(TrajectoryError, ACensoredAxisGivesTheOneSidedMisfitOfItsDefinition) {
  // A gyro at its rail R records ±R while the truth is at least that fast in that sense. Per censored axis: 0 when
  // the model is at or beyond the rail in the recorded sense, ω_m − ω_s (the shortfall) otherwise; the other axes
  // of the sample are plain. Cases written out by hand for R = 2 rad/s on x (+) and y (−).
  constexpr double kRail = 2.0;
  ErrorNodes nodes;
  nodes.w_m_B = {Eigen::Vector3d(kRail, -kRail, 0.5)};
  nodes.censored_axes = {0b011};
  struct Case {
    Eigen::Vector3d w_s;
    Eigen::Vector3d misfit;
  };
  const Case cases[] = {
      {{2.5, -2.5, 0.4}, {0.0, 0.0, 0.1}},    // beyond the rail on both censored axes: only z's plain misfit
      {{2.0, -2.0, 0.5}, {0.0, 0.0, 0.0}},    // exactly at the rail
      {{1.5, -1.0, 0.5}, {0.5, -1.0, 0.0}},   // short of the rail: the shortfall, in the recorded sense
      {{-1.0, 3.0, 0.0}, {3.0, -5.0, 0.5}},   // the wrong sense altogether
      {{3.0, -1.5, -0.5}, {0.0, -0.5, 1.0}},  // beyond on x, short on y
  };
  for (const Case& c : cases) {
    EXPECT_LT((NodeMisfit(nodes, 0, c.w_s) - c.misfit).norm(), kSumTolerance) << c.w_s.transpose();
  }
  nodes.censored_axes = {0};  // a plain sample: the plain difference
  EXPECT_LT((NodeMisfit(nodes, 0, Eigen::Vector3d(2.5, -2.5, 0.4)) - Eigen::Vector3d(-0.5, 0.5, 0.1)).norm(),
            kSumTolerance);
}

TEST(TrajectoryError, CensoredSamplesKeepTheirWeightAndEnterWithTheirMisfit) {
  // ω_m = c everywhere, model 0, samples 40–43 censored on x: c_x > 0 and the model (0) falls short of it, so the
  // misfit there is still c and ε = ‖c‖ over the whole window; with the model beyond the rail on x instead, those
  // samples contribute ‖(0, c_y, c_z)‖ and ε is the weighted mean of the two.
  const Eigen::Vector3d c(0.3, -0.4, 1.2);  // ‖c‖ = 1.3
  MeasuredSignal s = UniformSignal(256.0, 300, [&](double) { return c; });
  s.censored_axes.assign(s.size(), 0);
  s.excluded.assign(s.size(), false);
  for (std::size_t k : {40u, 41u, 42u, 43u}) {
    s.censored_axes[k] = 0b001;
    s.excluded[k] = true;  // as the trial problem marks a clipped sample for the phase-1 estimate and the noise floor
  }
  ErrorNodes nodes;
  ASSERT_TRUE(BuildErrorNodes(s, 0.0123, 1.0, &nodes));
  EXPECT_EQ(nodes.num_excluded, 0u);
  EXPECT_EQ(nodes.num_censored, 4u);
  EXPECT_NEAR(TrajectoryError(nodes, Zeros(nodes.size())), 1.3, kSumTolerance);
  std::vector<Eigen::Vector3d> w_s = Zeros(nodes.size());
  double censored_weight = 0.0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes.censored_axes[i] == 0) continue;
    w_s[i] = Eigen::Vector3d(1.0, 0.0, 0.0);  // beyond the rail c_x = 0.3
    censored_weight += nodes.weight_s[i];
  }
  const double expected =
      (1.3 * (nodes.duration_s() - censored_weight) + std::hypot(0.4, 1.2) * censored_weight) / nodes.duration_s();
  EXPECT_NEAR(TrajectoryError(nodes, w_s), expected, kSumTolerance);
}

TEST(TrajectoryError, SatisfiedCensoredAxesAreThoseWhereTheMisfitIsZeroByCensoring) {
  // The cases of the one-sided misfit above, R = 2 rad/s on x (+) and y (−): an axis is satisfied when the model
  // is at or beyond the rail in the recorded sense; a plain axis never is.
  constexpr double kRail = 2.0;
  ErrorNodes nodes;
  nodes.w_m_B = {Eigen::Vector3d(kRail, -kRail, 0.5)};
  nodes.censored_axes = {0b011};
  EXPECT_EQ(SatisfiedCensoredAxes(nodes, 0, Eigen::Vector3d(2.5, -2.5, 0.5)), 0b011);  // beyond on both
  EXPECT_EQ(SatisfiedCensoredAxes(nodes, 0, Eigen::Vector3d(2.0, -2.0, 9.0)), 0b011);  // at the rail
  EXPECT_EQ(SatisfiedCensoredAxes(nodes, 0, Eigen::Vector3d(1.5, -1.0, 0.5)), 0);      // short on both
  EXPECT_EQ(SatisfiedCensoredAxes(nodes, 0, Eigen::Vector3d(3.0, -1.5, 0.5)), 0b001);  // beyond on x only
  nodes.censored_axes = {0};
  EXPECT_EQ(SatisfiedCensoredAxes(nodes, 0, Eigen::Vector3d(2.5, -2.5, 0.5)), 0);
}

TEST(TrajectoryError, WithoutExcludedSamplesTheDivisorIsTheWindowExactly) {
  const MeasuredSignal s = UniformSignal(256.0, 300, [&](double t) { return Eigen::Vector3d(t, 0, 0); });
  ErrorNodes nodes;
  ASSERT_TRUE(BuildErrorNodes(s, 0.0123, 1.0, &nodes));
  EXPECT_EQ(nodes.excluded_weight_s, 0.0);
  EXPECT_EQ(nodes.weighted_duration_s(), nodes.duration_s());
}

TEST(TrajectoryError, IsInfiniteWhenEverySampleOfTheWindowIsExcluded) {
  MeasuredSignal s = UniformSignal(256.0, 50, [&](double) { return Eigen::Vector3d(1, 0, 0); });
  s.excluded.assign(s.size(), true);
  ErrorNodes nodes;
  ASSERT_TRUE(BuildErrorNodes(s, 0.01, 0.1, &nodes));
  EXPECT_TRUE(std::isinf(TrajectoryError(nodes, Zeros(nodes.size()))));
}

TEST(MeasuredSignal, ValidateRejectsExclusionMarksOfAnotherLength) {
  MeasuredSignal s = UniformSignal(256.0, 10, [&](double) { return Eigen::Vector3d::Zero(); });
  s.excluded.assign(9, false);
  EXPECT_THROW(s.Validate(), InvalidArgument);
}

TEST(MeasuredSignal, ValidateNamesTheFirstNonIncreasingSample) {
  MeasuredSignal s;
  s.t_s = {0.0, 0.1, 0.1};
  s.w_B.assign(3, Eigen::Vector3d::Zero());
  try {
    s.Validate();
    FAIL() << "expected InvalidArgument";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("sample 2"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rockfit::fitting
