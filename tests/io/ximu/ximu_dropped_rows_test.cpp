#include "ximu/ximu_dropped_rows.hpp"

#include <gtest/gtest.h>

namespace rockfit::io {
namespace {

// Packet numbers of n cycles of (inertial, attitude), the counter starting at `first`.
void Interleaved(std::size_t n, double first, std::vector<double>* inertial, std::vector<double>* attitude) {
  for (std::size_t k = 0; k < n; ++k) {
    inertial->push_back(first + 2.0 * static_cast<double>(k));
    attitude->push_back(first + 2.0 * static_cast<double>(k) + 1.0);
  }
}

TEST(FindMissingInertialRows, NoneWhereEveryIntervalHoldsOneAttitudePacket) {
  std::vector<double> inertial, attitude;
  Interleaved(100, 113.0, &inertial, &attitude);
  EXPECT_TRUE(FindMissingInertialRows(inertial, attitude).empty());
}

TEST(FindMissingInertialRows, TwoAttitudePacketsBetweenRowsMeanOneRowMissing) {
  std::vector<double> inertial, attitude;
  Interleaved(100, 1.0, &inertial, &attitude);
  inertial.erase(inertial.begin() + 40);                       // one row removed after row 39
  inertial.erase(inertial.begin() + 70, inertial.begin() + 73);  // three after row 69 (of the shortened list)
  const std::vector<MissingRows> missing = FindMissingInertialRows(inertial, attitude);
  ASSERT_EQ(missing.size(), 2u);
  EXPECT_EQ(missing[0].after_index, 39u);
  EXPECT_EQ(missing[0].missing, 1u);
  EXPECT_EQ(missing[1].after_index, 69u);
  EXPECT_EQ(missing[1].missing, 3u);
}

TEST(FindMissingInertialRows, AttitudeAtHalfTheRateSaysNothing) {
  std::vector<double> inertial, attitude;
  for (std::size_t k = 0; k < 100; ++k) {
    inertial.push_back(static_cast<double>(3 * k));
    if (k % 2 == 0) attitude.push_back(static_cast<double>(3 * k + 1));
  }
  EXPECT_TRUE(FindMissingInertialRows(inertial, attitude).empty());
}

TEST(TimesWithMissingRows, SkipsTheMissingSamplePeriods) {
  const std::vector<double> t = TimesWithMissingRows(5, 4.0, {{1, 2}});
  ASSERT_EQ(t.size(), 5u);
  EXPECT_DOUBLE_EQ(t[0], 0.0);
  EXPECT_DOUBLE_EQ(t[1], 0.25);
  EXPECT_DOUBLE_EQ(t[2], 1.0);  // rows at 0.5 and 0.75 s missing
  EXPECT_DOUBLE_EQ(t[4], 1.5);
}

}  // namespace
}  // namespace rockfit::io
