// The sampler's Euler angles by increments against the exact conversion of every sample's quaternion.
#include "detail/euler_zyx_sequence.hpp"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "rockfit/core/attitude.hpp"

namespace rockfit::core::detail {
namespace {

// Round-off of kExactEvery increments (a few units in the last place of angles up to π each).
constexpr double kSequenceTol_rad = 2e-14;

// A tumbling attitude: yaw, pitch and roll that sweep through their ranges, including yaw and roll across ±π and
// pitch towards the gimbal lock, at the given sample rate.
Eigen::Quaterniond Tumbling(double t_s) {
  return QuaternionFromEulerZyx(
      Eigen::Vector3d(3.0 * std::sin(0.7 * t_s) + 0.4 * t_s, 1.5705 * std::sin(0.9 * t_s), 2.0 * t_s + 0.1));
}

TEST(EulerZyxSequence, AnglesOfConsecutiveSamplesAreTheExactConversionsToRoundOff) {
  EulerZyxSequence sequence;
  const double rate_hz = 256.0;
  int checked = 0;
  for (std::size_t k = 0; k < 20000; ++k) {
    const Eigen::Quaterniond q = CanonicalUnitQuaternion(Tumbling(static_cast<double>(k) / rate_hz));
    const Eigen::Vector3d got = sequence.Next(q, k);
    const Eigen::Vector3d exact = EulerZyxFromUnitQuaternion(q);
    if (std::abs(exact[1]) > EulerZyxSequence::kMaxPitch_rad) continue;  // gimbal lock: its own convention
    EXPECT_NEAR(got[0], exact[0], kSequenceTol_rad) << k;
    EXPECT_NEAR(got[1], exact[1], kSequenceTol_rad) << k;
    EXPECT_NEAR(got[2], exact[2], kSequenceTol_rad) << k;
    ++checked;
  }
  EXPECT_GT(checked, 19000);
}

TEST(EulerZyxSequence, GapsAndLargeTurnsAreConvertedExactly) {
  EulerZyxSequence sequence;
  std::mt19937 rng(2711);
  std::normal_distribution<double> component(0.0, 1.0);
  std::size_t index = 0;
  for (int i = 0; i < 2000; ++i) {
    // Random attitudes (every increment large) with random gaps in the numbering.
    const Eigen::Quaterniond q = CanonicalUnitQuaternion(
        Eigen::Quaterniond(component(rng), component(rng), component(rng), component(rng)).normalized());
    index += 1 + (i % 3 == 0 ? 5 : 0);
    EXPECT_EQ(sequence.Next(q, index), EulerZyxFromUnitQuaternion(q)) << i;
  }
}

TEST(EulerZyxSequence, FirstSampleAndEveryKExactEveryAreExactBitForBit) {
  EulerZyxSequence sequence;
  for (std::size_t k = 0; k < 200; ++k) {
    const Eigen::Quaterniond q = CanonicalUnitQuaternion(Tumbling(0.3 + static_cast<double>(k) / 1024.0));
    const Eigen::Vector3d got = sequence.Next(q, k);
    if (k % (EulerZyxSequence::kExactEvery + 1) == 0) {
      EXPECT_EQ(got, EulerZyxFromUnitQuaternion(q)) << k;
    }
  }
}

}  // namespace
}  // namespace rockfit::core::detail
