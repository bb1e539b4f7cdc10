#include "ximu/ximu_rtc_rate.hpp"

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"

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

TEST(EstimateRateFromDateTime, AClockFieldOutOfRangeIsABadCellNamingLineAndColumn) {
  // A day of 4·10¹⁷ once overflowed the count of seconds (signed overflow, found by fuzzing).
  std::vector<std::string> warnings;
  const CsvTable date_time = CsvTable::FromText(
      "Packet number,Year,Month,Day,Hours,Minutes,Seconds\n0,2000,1,1,3,21,50\n111,2000,1,426666666666666651,3,21,50\n",
      "D.csv", warnings);
  try {
    EstimateRateFromDateTime(date_time, {0.0, 50.0, 111.0});
    FAIL();
  } catch (const BadInput& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("D.csv:3:"), std::string::npos) << what;
    EXPECT_NE(what.find("column 4 'Day'"), std::string::npos) << what;
    EXPECT_NE(what.find("a day of the month from 0 to 31"), std::string::npos) << what;
  }
  const CsvTable minutes = CsvTable::FromText(
      "Packet number,Year,Month,Day,Hours,Minutes,Seconds\n0,2000,1,1,3,60,50\n", "D.csv", warnings);
  EXPECT_THROW(EstimateRateFromDateTime(minutes, {0.0}), BadInput);
}

}  // namespace
}  // namespace rockfit::io
