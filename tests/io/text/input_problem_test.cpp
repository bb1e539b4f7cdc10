#include "text/input_problem.hpp"

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::io {
namespace {

TEST(FormatPosition, LeavesOutUnknownLineAndColumn) {
  EXPECT_EQ(FormatPosition({"a.csv", 12, 5}), "a.csv:12:5");
  EXPECT_EQ(FormatPosition({"a.csv", 12}), "a.csv:12");
  EXPECT_EQ(FormatPosition({"a.csv"}), "a.csv");
}

TEST(FormatProblem, SaysWhereWhatWasFoundWhatWasExpectedAndWhatToDo) {
  const std::string text = FormatProblem({{"a.csv", 3, 7}, "column 2 'Gyroscope X (deg/s)'", "'abc'", "a number",
                                          "Correct or delete line 3."});
  EXPECT_EQ(text, "a.csv:3:7: column 2 'Gyroscope X (deg/s)': found 'abc', expected a number. Correct or delete line 3.");
}

TEST(FormatProblem, ReadsWellWithoutSubjectOrPosition) {
  EXPECT_EQ(FormatProblem({{"a.csv"}, "", "an empty file", "a header", "Copy it again."}),
            "a.csv: found an empty file, expected a header. Copy it again.");
  EXPECT_EQ(FormatProblem({{}, "", "x", "y", ""}), "found x, expected y.");
}

TEST(ThrowBadInput, ThrowsTheFormattedMessageAsBadInput) {
  try {
    ThrowBadInput({{"b.csv", 1}, "", "f", "e", "t"});
    FAIL() << "no exception";
  } catch (const BadInput& e) {
    EXPECT_STREQ(e.what(), "b.csv:1: found f, expected e. t");
  }
}

TEST(QuoteCell, QuotesShortensAndEscapesControlCharacters) {
  EXPECT_EQ(QuoteCell("abc"), "'abc'");
  EXPECT_EQ(QuoteCell(""), "an empty cell");
  EXPECT_EQ(QuoteCell("a\x01"), "'a\\x01'");
  EXPECT_EQ(QuoteCell(std::string(50, 'x')), "'" + std::string(40, 'x') + "…'");
}

}  // namespace
}  // namespace rockfit::io
