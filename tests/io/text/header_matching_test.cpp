#include "text/header_matching.hpp"

#include <gtest/gtest.h>

namespace rockfit::io {
namespace {

TEST(NormalizeHeader, TrimsLowersAndCollapsesSpaces) {
  EXPECT_EQ(NormalizeHeader("  Packet   Number "), "packet number");
  EXPECT_EQ(NormalizeHeader(" Pitch | Theta | Y (degrees)"), "pitch | theta | y (degrees)");
}

TEST(HeaderEquals, AcceptsTheGuiVersionSpellings) {
  EXPECT_TRUE(HeaderEquals("Packet Number", "Packet number"));
  EXPECT_TRUE(HeaderEquals(" Element 2", "Element 2"));
  EXPECT_FALSE(HeaderEquals("Element 2", "Element 3"));
}

TEST(EditDistance, CountsInsertionsDeletionsAndSubstitutions) {
  EXPECT_EQ(EditDistance("kitten", "sitting"), 3u);
  EXPECT_EQ(EditDistance("", "abc"), 3u);
  EXPECT_EQ(EditDistance("abc", "abc"), 0u);
  EXPECT_EQ(EditDistance("gyroscop y", "gyroscope y"), 1u);
}

TEST(ClosestHeader, SuggestsAMisspellingButNotAnUnrelatedColumn) {
  const std::vector<std::string> header = {"Packet number", "Gyroscop Y (deg/s)", "Magnetometer X (G)"};
  const auto suggestion = ClosestHeader(header, {"Gyroscope Y (deg/s)"});
  ASSERT_TRUE(suggestion);
  EXPECT_EQ(suggestion->index, 1u);
  EXPECT_FALSE(ClosestHeader(header, {"Accelerometer Z (g)"}));
}

TEST(SplitHeaderUnit, SeparatesTheUnitInFinalSquareBrackets) {
  const HeaderParts parts = SplitHeaderUnit("gyro_x [deg/s]");
  EXPECT_EQ(parts.name, "gyro_x");
  EXPECT_EQ(parts.unit, "deg/s");
}

TEST(SplitHeaderUnit, SeparatesTheUnitInFinalParentheses) {
  const HeaderParts parts = SplitHeaderUnit(" Gyroscope X (deg/s) ");
  EXPECT_EQ(parts.name, "Gyroscope X");
  EXPECT_EQ(parts.unit, "deg/s");
  EXPECT_EQ(SplitHeaderUnit("Roll | Phi | X (degrees)").name, "Roll | Phi | X");
  EXPECT_EQ(SplitHeaderUnit("W").unit, "");
}

}  // namespace
}  // namespace rockfit::io
