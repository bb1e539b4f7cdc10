// The impact times estimated with the angle's error in one linear solve: readings made from the model itself
// (y_k = E_k + a_k·δ_k + Σ_{j<k} c_j·δ_j) give back their δ; what the data cannot tell stays at the prior.
#include "rockfit/io/joint_impact_times.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "rockfit/core/errors.hpp"

namespace rockfit::io {
namespace {

constexpr double kDt_s = 1.0 / 256.0;

std::vector<SplitInterval> Splits(const std::vector<int>& samples) {
  std::vector<SplitInterval> splits;
  for (int m : samples) splits.push_back({m * kDt_s, (m + 1) * kDt_s});
  return splits;
}

// Readings of one axis at every split, from true offsets δ, an error E(t) = e0 + β·t and rates a_k, rate jumps c_j.
AxisReadings ModelReadings(const std::vector<SplitInterval>& splits, const std::vector<double>& offsets_s,
                           const std::vector<double>& rates, const std::vector<double>& jumps, double e0_rad,
                           double bias_rad_s) {
  AxisReadings axis;
  axis.rate_jump_rad_s = jumps;
  for (std::size_t k = 0; k < splits.size(); ++k) {
    double y = e0_rad + bias_rad_s * splits[k].middle_s() + rates[k] * offsets_s[k];
    for (std::size_t j = 0; j < k; ++j) y += jumps[j] * offsets_s[j];
    axis.readings.push_back({k, y, rates[k]});
  }
  return axis;
}

// Tight scatter and walk: the readings are the model's, so the solution is the data's, not the priors'.
JointImpactOptions Exact() {
  JointImpactOptions o;
  o.reading_scatter_rad = 1e-9;
  o.drift_walk_rad_per_sqrt_s = 1e-9;
  return o;
}

TEST(EstimateJointImpactTimes, ReadingsOfTheModelGiveBackTheOffsetsWhereSmallLateImpactsPinTheError) {
  // Five rocking impacts (rate falling by 0.8, jump 15 % of it, alternating sign), then three small late ones
  // whose rate is zero: they read E alone and fix its level and trend, so every δ of the first five follows.
  const std::vector<SplitInterval> splits = Splits({400, 460, 510, 550, 585, 640, 700, 760});
  std::mt19937 draw(29);
  std::uniform_real_distribution<double> within(-0.5 * kDt_s, 0.5 * kDt_s);
  std::vector<double> offsets, rates, jumps;
  for (std::size_t k = 0; k < splits.size(); ++k) {
    const double a = k < 5 ? std::pow(-0.8, static_cast<double>(k)) : 0.0;
    rates.push_back(a);
    jumps.push_back(0.15 * a);
    offsets.push_back(k < 5 ? within(draw) : 0.0);
  }
  const AxisReadings axis = ModelReadings(splits, offsets, rates, jumps, 1.3e-3, -2e-4);
  const JointImpactSummary s = EstimateJointImpactTimes(splits, {axis}, Exact());
  ASSERT_EQ(s.times_s.size(), splits.size());
  for (std::size_t k = 0; k < 5; ++k) {
    EXPECT_NEAR(s.offsets_s[k], offsets[k], 1e-9) << "impact " << k;
    EXPECT_NEAR(s.times_s[k], splits[k].middle_s() - offsets[k], 1e-9);
    EXPECT_NEAR(s.errors_rad[0][k], 1.3e-3 - 2e-4 * splits[k].middle_s(), 1e-9);
  }
  // No rate, no jump: nothing tells where in their intervals the last three are; they stay at the middle.
  for (std::size_t k = 5; k < splits.size(); ++k) EXPECT_NEAR(s.offsets_s[k], 0.0, 1e-12);
}

TEST(EstimateJointImpactTimes, TheStepOfAnEarlierSplitEntersEveryLaterReading) {
  // Impact 1 has no reading of its own on this axis (only its jump); later readings see its step c_1·δ_1: with
  // E pinned by rate-free readings the step alone gives δ_1 = step / c_1.
  // A reading before the split, at rate zero, fixes E before the step; three after it read E plus the step.
  const double delta1_s = 1e-3;
  const double e_rad = 5e-4;
  const std::vector<SplitInterval> with_first = Splits({50, 100, 200, 300, 400});
  AxisReadings first;
  first.rate_jump_rad_s = {0.0, 0.4, 0.0, 0.0, 0.0};
  first.readings.push_back({0, e_rad, 0.0});
  for (std::size_t k = 2; k < with_first.size(); ++k) first.readings.push_back({k, e_rad + 0.4 * delta1_s, 0.0});
  const JointImpactSummary s = EstimateJointImpactTimes(with_first, {first}, Exact());
  EXPECT_NEAR(s.offsets_s[1], delta1_s, 1e-9);
  EXPECT_NEAR(s.times_s[1], with_first[1].middle_s() - delta1_s, 1e-9);
}

TEST(EstimateJointImpactTimes, TwoAxesShareTheOffsetOfASplit) {
  // φ_y reads E only (rate zero at all its readings); φ_x sees the impact at split 1 with rate 0.5: δ_1 comes from
  // φ_x, and φ_y's later reading carries the step of φ_y's own jump there.
  const std::vector<SplitInterval> splits = Splits({100, 160, 220, 280});
  const double delta1_s = -1.2e-3;
  AxisReadings y;
  y.rate_jump_rad_s = {0.0, 0.3, 0.0, 0.0};
  y.readings = {{0, 0.0, 0.0}, {2, 0.3 * delta1_s, 0.0}, {3, 0.3 * delta1_s, 0.0}};
  AxisReadings x;
  x.rate_jump_rad_s = {0.0, 0.0, 0.0, 0.0};
  x.readings = {{0, 2e-3, 0.0}, {1, 2e-3 + 0.5 * delta1_s, 0.5}, {2, 2e-3, 0.0}, {3, 2e-3, 0.0}};
  const JointImpactSummary s = EstimateJointImpactTimes(splits, {y, x}, Exact());
  EXPECT_NEAR(s.offsets_s[1], delta1_s, 1e-9);
}

TEST(EstimateJointImpactTimes, ALoneImpactStaysAtItsMiddle) {
  // One reading: its error and its offset cannot be told apart, and the error's prior is far looser.
  const std::vector<SplitInterval> splits = Splits({300});
  AxisReadings axis;
  axis.rate_jump_rad_s = {0.2};
  axis.readings = {{0, 3e-3, 1.0}};
  const JointImpactSummary s = EstimateJointImpactTimes(splits, {axis}, JointImpactOptions{});
  EXPECT_NEAR(s.offsets_s[0], 0.0, 1e-3 * kDt_s);
  EXPECT_NEAR(s.errors_rad[0][0], 3e-3, 1e-6);
}

TEST(EstimateJointImpactTimes, AnOffsetBeyondTheIntervalIsHeldAtItsEnd) {
  // The model asks for δ = 3 ms, beyond Δt/2 ≈ 1.95 ms: τ is held at the interval's start.
  const std::vector<SplitInterval> splits = Splits({100, 200, 300});
  AxisReadings axis;
  axis.rate_jump_rad_s = {0.0, 0.0, 0.0};
  axis.readings = {{0, 0.0, 0.0}, {1, 1.0 * 3e-3, 1.0}, {2, 0.0, 0.0}};
  const JointImpactSummary s = EstimateJointImpactTimes(splits, {axis}, Exact());
  EXPECT_DOUBLE_EQ(s.offsets_s[1], 0.5 * kDt_s);
  EXPECT_DOUBLE_EQ(s.times_s[1], splits[1].t0_s);
}

TEST(EstimateJointImpactTimes, InconsistentInputIsRefused) {
  const std::vector<SplitInterval> splits = Splits({100, 200});
  AxisReadings axis;
  axis.rate_jump_rad_s = {0.0, 0.0};
  axis.readings = {{0, 0.0, 1.0}, {1, 0.0, 1.0}};
  EXPECT_NO_THROW(EstimateJointImpactTimes(splits, {axis}, {}));
  EXPECT_THROW(EstimateJointImpactTimes(Splits({200, 100}), {axis}, {}), InvalidArgument);  // not in time order
  AxisReadings short_jumps = axis;
  short_jumps.rate_jump_rad_s = {0.0};
  EXPECT_THROW(EstimateJointImpactTimes(splits, {short_jumps}, {}), InvalidArgument);
  AxisReadings beyond = axis;
  beyond.readings.push_back({5, 0.0, 1.0});
  EXPECT_THROW(EstimateJointImpactTimes(splits, {beyond}, {}), InvalidArgument);  // no split 5
  AxisReadings backwards = axis;
  std::swap(backwards.readings[0], backwards.readings[1]);
  EXPECT_THROW(EstimateJointImpactTimes(splits, {backwards}, {}), InvalidArgument);
  JointImpactOptions o;
  o.reading_scatter_rad = 0.0;
  EXPECT_THROW(o.Validate(), InvalidArgument);
  o = {};
  o.drift_walk_rad_per_sqrt_s = std::nan("");
  EXPECT_THROW(o.Validate(), InvalidArgument);
}

}  // namespace
}  // namespace rockfit::io
