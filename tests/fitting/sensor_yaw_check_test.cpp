// The turn about block z from the fitted motion: recovered from data that are the model turned (with noise), not
// claimed for data the model meets, and given back as the mounting that undoes it.
#include "rockfit/fitting/sensor_yaw_check.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Geometry>

namespace rockfit::fitting {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Nodes 1/256 s apart whose measured rate is the model's turned by `yaw_deg` about z plus white noise of
// `noise_rad_s` per axis; the model: a rocking rate about y with a small x part and a z part.
struct TurnedData {
  ErrorNodes nodes;
  std::vector<Eigen::Vector3d> w_s_B;
};

TurnedData MakeTurnedData(double yaw_deg, double noise_rad_s, unsigned seed) {
  TurnedData d;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, noise_rad_s);
  const Eigen::AngleAxisd turn(yaw_deg * kPi / 180.0, Eigen::Vector3d::UnitZ());
  const std::size_t n = 512;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / 256.0;
    const Eigen::Vector3d s(0.2 * std::sin(9.0 * t), 1.5 * std::cos(6.0 * t) * std::exp(-t), 0.05 * std::sin(3.0 * t));
    d.w_s_B.push_back(s);
    d.nodes.t_s.push_back(t);
    d.nodes.t_after_release_s.push_back(t);
    d.nodes.w_m_B.push_back(turn * s + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
    d.nodes.weight_s.push_back(i == 0 || i + 1 == n ? 0.5 / 256.0 : 1.0 / 256.0);
  }
  d.nodes.censored_axes.assign(n, 0);
  return d;
}

TEST(SensorYawCheck, RecoversTheTurnOfDataThatAreTheModelTurned) {
  for (double yaw_deg : {-5.0, -2.0, 1.5, 3.0}) {
    const TurnedData d = MakeTurnedData(yaw_deg, 0.005, 3);
    const SensorYawCheck c = CheckSensorYaw(d.nodes, d.w_s_B, io::Mounting());
    ASSERT_TRUE(c.available);
    EXPECT_NEAR(c.yaw_deg, yaw_deg, 0.05);
    EXPECT_TRUE(c.turned) << yaw_deg;  // |ψ| ≥ 1° and the turned model's (28) at most 0.8 of the fit's
    // The mounting that undoes it: R_BS = Rz(−ψ), whose turn about z is −ψ.
    const Eigen::Quaterniond q = io::Mounting::Parse(c.corrected_mounting).q_BS();
    const Eigen::AngleAxisd expected(-c.yaw_deg * kPi / 180.0, Eigen::Vector3d::UnitZ());
    EXPECT_LT(q.angularDistance(Eigen::Quaterniond(expected)), 1e-6);
  }
}

TEST(SensorYawCheck, DataTheModelMeetsAreNotCalledTurned) {
  const TurnedData d = MakeTurnedData(0.0, 0.005, 4);
  const SensorYawCheck c = CheckSensorYaw(d.nodes, d.w_s_B, io::Mounting());
  ASSERT_TRUE(c.available);
  EXPECT_LT(std::abs(c.yaw_deg), 0.1);
  EXPECT_FALSE(c.turned);
  // A turn below the warning threshold is not called one either, however well it explains the misfit.
  const TurnedData small = MakeTurnedData(0.6, 0.0005, 5);
  const SensorYawCheck s = CheckSensorYaw(small.nodes, small.w_s_B, io::Mounting());
  EXPECT_NEAR(s.yaw_deg, 0.6, 0.01);
  EXPECT_LT(s.epsilon_turned_rad_s, 0.5 * s.epsilon_rad_s);
  EXPECT_FALSE(s.turned);
}

TEST(SensorYawCheck, ATurnThatExplainsLittleOfTheMisfitIsNotCalledTurned) {
  // Data turned by 2° under noise far larger than the turn's effect: the turn is found, but it does not lower (28)
  // to 0.8 of the fit's — the misfit is something else.
  const TurnedData d = MakeTurnedData(2.0, 0.3, 6);
  const SensorYawCheck c = CheckSensorYaw(d.nodes, d.w_s_B, io::Mounting());
  ASSERT_TRUE(c.available);
  EXPECT_GT(c.epsilon_turned_rad_s, kSensorYawMaxEpsilonRatio * c.epsilon_rad_s);
  EXPECT_FALSE(c.turned);
}

TEST(SensorYawCheck, TheCorrectedMountingTurnsTheAppliedOneAboutBlockZ) {
  // Applied: the sensor upside down ("x,-y,-z"); the data turned by 3° after it. The mounting that undoes it maps
  // the sensor's rate to block axes turned back by 3°: q = Rz(−3°)·q_applied.
  const TurnedData d = MakeTurnedData(3.0, 0.002, 7);
  const io::Mounting applied = io::Mounting::Parse("x,-y,-z");
  const SensorYawCheck c = CheckSensorYaw(d.nodes, d.w_s_B, applied);
  ASSERT_TRUE(c.turned);
  const Eigen::Quaterniond q = io::Mounting::Parse(c.corrected_mounting).q_BS();
  const Eigen::Quaterniond expected =
      Eigen::Quaterniond(Eigen::AngleAxisd(-c.yaw_deg * kPi / 180.0, Eigen::Vector3d::UnitZ())) * applied.q_BS();
  EXPECT_LT(q.angularDistance(expected), 1e-6);
}

TEST(SensorYawCheck, NoRateInThePlaneGivesNoCheck) {
  TurnedData d = MakeTurnedData(0.0, 0.0, 8);
  for (Eigen::Vector3d& s : d.w_s_B) s = Eigen::Vector3d(0.0, 0.0, 0.1);
  EXPECT_FALSE(CheckSensorYaw(d.nodes, d.w_s_B, io::Mounting()).available);
  d.w_s_B.pop_back();  // a model output of the wrong length
  EXPECT_FALSE(CheckSensorYaw(d.nodes, d.w_s_B, io::Mounting()).available);
}

}  // namespace
}  // namespace rockfit::fitting
