#include "text/number_parsing.hpp"

#include <clocale>
#include <cmath>

#include <gtest/gtest.h>

namespace rockfit::io {
namespace {

TEST(ParseReal, ReadsTheExponentFormTheXimuGuiWrites) {
  const ParsedNumber number = ParseReal("-6.113857E-05");
  ASSERT_EQ(number.status, NumberStatus::kOk);
  EXPECT_DOUBLE_EQ(number.value, -6.113857e-05);
}

TEST(ParseReal, IgnoresSurroundingSpacesAndALeadingPlus) {
  EXPECT_DOUBLE_EQ(ParseReal("  +1.5\t").value, 1.5);
  EXPECT_EQ(ParseReal(" 0.9999776 ").status, NumberStatus::kOk);
  EXPECT_DOUBLE_EQ(ParseReal("-0.000000").value, 0.0);
  EXPECT_TRUE(std::signbit(ParseReal("-0.000000").value));
}

TEST(ParseReal, ClassifiesNaNAndInfinityWhateverTheirCase) {
  EXPECT_EQ(ParseReal("NaN").status, NumberStatus::kNaN);
  EXPECT_EQ(ParseReal("nan").status, NumberStatus::kNaN);
  EXPECT_EQ(ParseReal("Infinity").status, NumberStatus::kInfinite);
  EXPECT_EQ(ParseReal("-inf").status, NumberStatus::kInfinite);
  EXPECT_EQ(ParseReal("1e400").status, NumberStatus::kOutOfRange);
}

TEST(ParseReal, ReportsADecimalCommaInAFileThatUsesTheDecimalPoint) {
  EXPECT_EQ(ParseReal("1,25").status, NumberStatus::kDecimalComma);
  EXPECT_EQ(ParseReal("-0,0625").status, NumberStatus::kDecimalComma);
  EXPECT_EQ(ParseReal("a,b").status, NumberStatus::kNotANumber);
  EXPECT_EQ(ParseReal("1,2,3").status, NumberStatus::kNotANumber);
}

TEST(ParseReal, ReadsDecimalCommasWhenTheCommaCannotBeASeparator) {
  EXPECT_DOUBLE_EQ(ParseReal("1,25", DecimalSeparator::kComma).value, 1.25);
  EXPECT_DOUBLE_EQ(ParseReal("-6,113857E-05", DecimalSeparator::kComma).value, -6.113857e-05);
  EXPECT_EQ(ParseReal("1.234,5", DecimalSeparator::kComma).status, NumberStatus::kNotANumber);
}

TEST(ParseReal, RejectsTextAndPartialNumbers) {
  for (const char* text : {"abc", "1.2.3", "1e", "--1", "+", "+-1", "0x10", "1 2", "12a", "∞"}) {
    EXPECT_EQ(ParseReal(text).status, NumberStatus::kNotANumber) << text;
  }
  EXPECT_EQ(ParseReal("").status, NumberStatus::kEmpty);
  EXPECT_EQ(ParseReal("   ").status, NumberStatus::kEmpty);
  EXPECT_EQ(ParseReal(std::string(100, '1')).status, NumberStatus::kNotANumber);
}

TEST(ParseReal, DoesNotDependOnTheProcessLocale) {
  // A locale with a decimal comma would make strtod read "1.5" as 1; from_chars never looks at it.
  const char* const previous = std::setlocale(LC_NUMERIC, nullptr);
  const std::string saved = previous ? previous : "C";
  if (!std::setlocale(LC_NUMERIC, "de_DE.UTF-8") && !std::setlocale(LC_NUMERIC, "hu_HU.UTF-8")) {
    GTEST_SKIP() << "no locale with a decimal comma installed";
  }
  const double value = ParseReal("1.5").value;
  std::setlocale(LC_NUMERIC, saved.c_str());
  EXPECT_DOUBLE_EQ(value, 1.5);
}

TEST(ParseInteger, AcceptsOnlyWholeNumbers) {
  EXPECT_EQ(ParseInteger("24231"), 24231);
  EXPECT_EQ(ParseInteger(" -3 "), -3);
  EXPECT_EQ(ParseInteger("+19150794"), 19150794);
  EXPECT_FALSE(ParseInteger("1.0"));
  EXPECT_FALSE(ParseInteger(""));
  EXPECT_FALSE(ParseInteger("12a"));
  EXPECT_FALSE(ParseInteger("99999999999999999999999"));
}

TEST(TrimSpaces, RemovesSpacesAndTabsAtBothEndsOnly) {
  EXPECT_EQ(TrimSpaces(" \t Element 2 \t"), "Element 2");
  EXPECT_EQ(TrimSpaces("   "), "");
}

}  // namespace
}  // namespace rockfit::io
