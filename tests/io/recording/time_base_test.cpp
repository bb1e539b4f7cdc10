#include "recording/time_base.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::io {
namespace {

using ::testing::HasSubstr;

CsvTable Table(const std::string& text) {
  std::vector<std::string> warnings;
  return CsvTable::FromText(text, "t.csv", warnings);
}

TEST(TimeBase, UniformTimesAreKOverTheRate) {
  const std::vector<double> t = UniformTimes(5, 256.0);
  ASSERT_EQ(t.size(), 5u);
  EXPECT_DOUBLE_EQ(t[0], 0.0);
  EXPECT_DOUBLE_EQ(t[4], 4.0 / 256.0);
}

TEST(TimeBase, RateIsOneOverTheMedianStepAndLongStepsAreGaps) {
  // 50 Hz with jitter and one lost sample (a 40 ms step), times not starting at 0.
  const std::vector<double> times = {19.150794, 19.170785, 19.190775, 19.230755, 19.250745, 19.270736};
  const TimestampTimeBase base = TimeBaseFromTimestamps(times);
  // Steps 19991, 19990, 39980, 19990, 19991 µs: the median is 19991 µs.
  EXPECT_NEAR(base.median_step_s, 0.019991, 1e-9);
  EXPECT_NEAR(base.rate_hz, 1.0 / 0.019991, 1e-6);
  EXPECT_DOUBLE_EQ(base.t_s.front(), 0.0);
  EXPECT_NEAR(base.t_s.back(), 19.270736 - 19.150794, 1e-12);
  ASSERT_EQ(base.gaps.size(), 1u);
  EXPECT_EQ(base.gaps[0].index, 2u);
  EXPECT_NEAR(base.gaps[0].duration_s, 0.03998, 1e-9);
  EXPECT_EQ(base.gaps[0].missing, 1u);
}

TEST(TimeBase, CountsTheSamplesMissingInALongGap) {
  const std::vector<Gap> gaps = FindGaps({0.0, 0.01, 0.02, 0.08, 0.09}, 0.01);
  ASSERT_EQ(gaps.size(), 1u);
  EXPECT_EQ(gaps[0].missing, 5u);
}

TEST(TimeBase, RefusesRepeatedAndDecreasingValuesNamingBothLines) {
  const CsvTable repeated = Table("Timestamp (us)\n10\n20\n20\n");
  try {
    ReadIncreasingColumn(repeated, 0, true, "Delete it.");
    FAIL() << "no exception";
  } catch (const BadInput& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("t.csv:4:1"), HasSubstr("'20' again (as on line 3)"), HasSubstr("Delete it.")));
  }
  const CsvTable decreasing = Table("Timestamp (us)\n10\n30\n20\n");
  try {
    ReadIncreasingColumn(decreasing, 0, true, "");
    FAIL() << "no exception";
  } catch (const BadInput& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("t.csv:4:1"), HasSubstr("'20', smaller than '30' on line 3"),
                                HasSubstr("values that increase")));
  }
  EXPECT_EQ(ReadIncreasingColumn(Table("t\n0.5\n0.75\n"), 0, false, "").back(), 0.75);
}

}  // namespace
}  // namespace rockfit::io
