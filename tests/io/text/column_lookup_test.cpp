#include "text/column_lookup.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/io/units.hpp"

namespace rockfit::io {
namespace {

using ::testing::HasSubstr;

CsvTable Table(const std::string& header) {
  std::vector<std::string> warnings;
  return CsvTable::FromText(header + "\n" + std::string(std::count(header.begin(), header.end(), ','), ',') + "\n",
                            "t.csv", warnings);
}

std::string ResolveError(const CsvTable& table, const std::vector<ColumnSpec>& specs) {
  try {
    ResolveColumns(table, specs);
  } catch (const BadInput& e) {
    return e.what();
  }
  return "";
}

TEST(ResolveColumns, FindsColumnsByNameNotPosition) {
  const CsvTable table = Table("Gyroscope Z (deg/s), Packet Number,Gyroscope X (deg/s)");
  const auto columns = ResolveColumns(table, {{{"Packet number"}, "counter"},
                                              {{"Gyroscope X (deg/s)"}, "x"},
                                              {{"Gyroscope Y (deg/s)"}, "y", false}});
  EXPECT_EQ(columns[0], 1u);
  EXPECT_EQ(columns[1], 2u);
  EXPECT_FALSE(columns[2]);
}

TEST(ResolveColumns, MatchesTheNameBeforeTheUnitWhenAsked) {
  const CsvTable table = Table("Roll | Phi | X (deg),Pitch | Theta | Y (degrees)");
  const auto columns = ResolveColumns(table, {{{"Roll | Phi | X"}, "roll", true, true}, {{"Pitch | Theta | Y"}, "pitch", true, true}});
  EXPECT_EQ(columns[0], 0u);
  EXPECT_EQ(columns[1], 1u);
  EXPECT_EQ(HeaderUnit(table, 0, &ParseAngleUnit, "deg, rad"), AngleUnit::kDegrees);
}

TEST(ResolveColumns, SuggestsTheClosestUnclaimedHeaderForAMisspelledColumn) {
  const CsvTable table = Table("Packet number,Gyroscope X (deg/s),Gyroscop Y (deg/s),Gyroscope Z (deg/s)");
  const std::string message = ResolveError(table, {{{"Gyroscope X (deg/s)"}, "x"}, {{"Gyroscope Y (deg/s)"}, "the y axis"},
                                                   {{"Gyroscope Z (deg/s)"}, "z"}});
  EXPECT_EQ(message,
            "t.csv:1:35: found the header 'Gyroscop Y (deg/s)', expected a column 'Gyroscope Y (deg/s)' (the y axis). If "
            "this is that column, rename its header to 'Gyroscope Y (deg/s)'.");
}

TEST(ResolveColumns, ListsTheHeaderWhenNothingIsClose) {
  const CsvTable table = Table("Packet number,Gyroscope X (deg/s)");
  EXPECT_THAT(ResolveError(table, {{{"Accelerometer Z (g)"}, "z"}}),
              AllOf(HasSubstr("t.csv:1: found the header 'Packet number', 'Gyroscope X (deg/s)'"),
                    HasSubstr("expected a column 'Accelerometer Z (g)'"), HasSubstr("Add the column")));
}

TEST(ResolveColumns, RefusesAColumnNamedTwice) {
  const CsvTable table = Table("W,X,x");
  EXPECT_THAT(ResolveError(table, {{{"X"}, "x"}}), AllOf(HasSubstr("t.csv:1:5"), HasSubstr("a second column named 'x'")));
}

TEST(HeaderUnit, RefusesAMissingOrUnknownUnit) {
  const CsvTable table = Table("Gyroscope X,Gyroscope Y (furlong/s)");
  try {
    HeaderUnit(table, 0, &ParseAngularRateUnit, "deg/s, rad/s");
    FAIL() << "no exception";
  } catch (const BadInput& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("t.csv:1:1"), HasSubstr("no unit in parentheses"), HasSubstr("Gyroscope X (deg/s)")));
  }
  EXPECT_THROW(HeaderUnit(table, 1, &ParseAngularRateUnit, "deg/s, rad/s"), BadInput);
}

}  // namespace
}  // namespace rockfit::io
