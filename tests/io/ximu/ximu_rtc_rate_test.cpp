#include "ximu/ximu_rtc_rate.hpp"

#include <gtest/gtest.h>

#include "imu_test_files.hpp"

namespace rockfit::io {
namespace {

// Packet numbers of the inertial rows of a GUI file, read back from its text.
std::vector<double> Packets(const std::string& inertial) {
  std::vector<double> packets;
  std::size_t at = inertial.find('\n') + 1;
  while (at < inertial.size()) {
    packets.push_back(std::stod(inertial.substr(at, inertial.find(',', at) - at)));
    at = inertial.find('\n', at) + 1;
  }
  return packets;
}

TEST(EstimateRateFromDateTime, CountsInertialRowsPerClockSecond) {
  const testing::GuiSpin spin = testing::MakeGuiSpin(128 * 6, 128.0, 10.0);
  std::vector<std::string> warnings;
  const CsvTable date_time = CsvTable::FromText(spin.date_time, "D.csv", warnings);
  const auto estimate = EstimateRateFromDateTime(date_time, Packets(spin.inertial));
  ASSERT_TRUE(estimate);
  EXPECT_EQ(estimate->rows_per_second, 128.0);
  EXPECT_EQ(estimate->seconds, 4u);  // 6 s of data: 5 changes of the second, 4 whole seconds between them
}

TEST(EstimateRateFromDateTime, NeedsTwoWholeSeconds) {
  const testing::GuiSpin spin = testing::MakeGuiSpin(256 * 2, 256.0, 10.0);
  std::vector<std::string> warnings;
  const CsvTable date_time = CsvTable::FromText(spin.date_time, "D.csv", warnings);
  EXPECT_FALSE(EstimateRateFromDateTime(date_time, Packets(spin.inertial)));
}

}  // namespace
}  // namespace rockfit::io
