#include "text/csv_table.hpp"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"
#include "scratch_dir.hpp"

namespace rockfit::io {
namespace {

using ::testing::HasSubstr;

CsvTable Parse(const std::string& text, std::vector<std::string>* warnings = nullptr) {
  std::vector<std::string> local;
  return CsvTable::FromText(text, "t.csv", warnings ? *warnings : local);
}

// The message of the BadInput that parsing `text` throws ("" if none).
std::string ParseError(const std::string& text) {
  try {
    Parse(text);
  } catch (const BadInput& e) {
    return e.what();
  }
  return "";
}

TEST(CsvTable, ReadsLfCrlfAndCrLineEndsAlike) {
  for (const std::string eol : {"\n", "\r\n", "\r"}) {
    const CsvTable table = Parse("a,b" + eol + "1,2" + eol + "3,4" + eol);
    ASSERT_EQ(table.row_count(), 2u) << "eol size " << eol.size();
    EXPECT_EQ(table.Cell(1, 1), "4");
    EXPECT_EQ(table.Line(1), 3u);
    EXPECT_FALSE(table.IsUnterminatedLastRow(1));
  }
}

TEST(CsvTable, TrimsCellsAndFindsPositionsFromTheLineStart) {
  const CsvTable table = Parse("Packet number,Element 1, Element 2\n1, 0.5 ,  -6.1E-05\n");
  EXPECT_EQ(table.header()[2], "Element 2");
  EXPECT_EQ(table.Cell(0, 2), "-6.1E-05");
  EXPECT_EQ(table.PositionOf(0, 2).column, 11u);  // "1, 0.5 ,  -" — the cell starts at byte 11
  EXPECT_EQ(table.HeaderPosition(2).column, 26u);  // after "Packet number,Element 1, "
  EXPECT_DOUBLE_EQ(table.Real(0, 2), -6.1e-05);
}

TEST(CsvTable, RemovesAUtf8ByteOrderMarkWithAWarning) {
  std::vector<std::string> warnings;
  const CsvTable table = Parse("\xef\xbb\xbf" "a,b\n1,2\n", &warnings);
  EXPECT_EQ(table.header()[0], "a");
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_THAT(warnings[0], HasSubstr("byte-order mark"));
}

TEST(CsvTable, RefusesUtf16AndBinaryFiles) {
  EXPECT_THAT(ParseError("\xff\xfe" "a\0,\0b\0"), HasSubstr("UTF-16"));
  EXPECT_THAT(ParseError(std::string("a,b\n1,\0\n", 8)), AllOf(HasSubstr("t.csv:2"), HasSubstr("NUL byte")));
}

TEST(CsvTable, RefusesEmptyFilesHeaderOnlyFilesAndFilesWithoutHeader) {
  EXPECT_THAT(ParseError(""), HasSubstr("t.csv: found an empty file (0 bytes)"));
  EXPECT_THAT(ParseError("\n \n"), HasSubstr("only blank lines"));
  EXPECT_THAT(ParseError("a,b\r\n"), HasSubstr("t.csv:1: found only the header line"));
  EXPECT_THAT(ParseError("0,1.5,2\n2,1.5,3\n"), AllOf(HasSubstr("t.csv:1:1"), HasSubstr("a header line")));
}

TEST(CsvTable, IgnoresATrailingSeparatorAsTheDigitalIoFileHasIt) {
  const CsvTable table = Parse("a,b,\n1,2,\n3,4\n");
  EXPECT_EQ(table.column_count(), 2u);
  EXPECT_EQ(table.row_count(), 2u);
}

TEST(CsvTable, SkipsBlankLinesWithAWarning) {
  std::vector<std::string> warnings;
  const CsvTable table = Parse("a\n1\n\n2\n\n", &warnings);
  EXPECT_EQ(table.row_count(), 2u);
  EXPECT_EQ(table.Line(1), 4u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_THAT(warnings[0], HasSubstr("t.csv:3: 2 blank lines"));
}

TEST(CsvTable, DropsALastLineThatWasCutOffWhileWritingWithAWarning) {
  std::vector<std::string> warnings;
  const CsvTable table = Parse("a,b,c\n1,2,3\n4,5", &warnings);
  EXPECT_EQ(table.row_count(), 1u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_THAT(warnings[0], HasSubstr("t.csv:3: the last line has 2 of 3 fields and no line end"));

  warnings.clear();
  EXPECT_EQ(Parse("a,b,c\n1,2,3\n4,5,", &warnings).row_count(), 1u);
  EXPECT_EQ(warnings.size(), 1u);
}

TEST(CsvTable, KeepsACompleteLastLineWithoutLineEnd) {
  std::vector<std::string> warnings;
  const CsvTable table = Parse("a,b\n1,2\n3,4", &warnings);
  EXPECT_EQ(table.row_count(), 2u);
  EXPECT_TRUE(table.IsUnterminatedLastRow(1));
  EXPECT_TRUE(warnings.empty());
}

TEST(CsvTable, ACutNumberInTheLastLineIsReportedWithTheLikelyCause) {
  const CsvTable table = Parse("a,b\n1,2\n3,4.5E");
  try {
    table.Real(1, 1);
    FAIL() << "no exception";
  } catch (const BadInput& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("t.csv:3:3"), HasSubstr("'4.5E'"), HasSubstr("cut off")));
  }
}

TEST(CsvTable, RefusesRowsOfTheWrongLengthNamingLineAndCounts) {
  EXPECT_THAT(ParseError("a,b,c\n1,2,3\n4,5\n6,7,8\n"),
              AllOf(HasSubstr("t.csv:3:1: found 2 fields, expected 3 fields, one per column of the header on line 1"),
                    HasSubstr("Correct or delete line 3")));
  EXPECT_THAT(ParseError("a,b\n1,2\n3,4,5\n"), AllOf(HasSubstr("t.csv:3:5: found 3 fields"), HasSubstr("decimal commas")));
}

TEST(CsvTable, RecognisesRowsWrittenWithDecimalCommas) {
  // x-IMU GUI ≤ 13.1 on a Hungarian/German Windows: "-0,125" for -0.125.
  const std::string text =
      "Packet number,Gyroscope X (deg/s),Gyroscope Y (deg/s),Gyroscope Z (deg/s)\n0,-0,125,-0,0625,0,125\n";
  EXPECT_THAT(ParseError(text), AllOf(HasSubstr("t.csv:2:5:"), HasSubstr("7 fields and numbers written with a decimal comma ('0,-0,125,-0,0625,0,125')"),
                                      HasSubstr("expected 4 fields"), HasSubstr("x-IMU GUI 13.2")));
}

TEST(CsvTable, ReadsSemicolonFilesWithDecimalCommasWithWarnings) {
  std::vector<std::string> warnings;
  const CsvTable table = Parse("a;b\n1,25;-6,5E-01\n", &warnings);
  EXPECT_EQ(table.delimiter(), ';');
  EXPECT_DOUBLE_EQ(table.Real(0, 0), 1.25);
  EXPECT_DOUBLE_EQ(table.Real(0, 1), -0.65);
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_THAT(warnings[0], HasSubstr("separated by ';'"));
  EXPECT_THAT(warnings[1], HasSubstr("t.csv:2: numbers are written with decimal commas"));
}

TEST(CsvTable, ReadsTabSeparatedFiles) {
  const CsvTable table = Parse("a\tb c\n1\t2\n");
  EXPECT_EQ(table.delimiter(), '\t');
  EXPECT_EQ(table.header()[1], "b c");
  EXPECT_DOUBLE_EQ(table.Real(0, 1), 2.0);
}

TEST(CsvTable, NumberErrorsNameFileLineColumnHeaderAndWhatToDo) {
  const CsvTable table = Parse("t,Gyroscope X (deg/s)\n0,abc\n1,\n2,NaN\n3,-Infinity\n4,1e999\n");
  const auto message = [&table](std::size_t row) {
    try {
      table.Real(row, 1);
    } catch (const BadInput& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message(0),
            "t.csv:2:3: column 2 'Gyroscope X (deg/s)': found 'abc', expected a number such as -0.0625 or "
            "-6.113857E-05. Correct or delete line 2.");
  EXPECT_THAT(message(1), HasSubstr("t.csv:3:3: column 2 'Gyroscope X (deg/s)': found an empty cell"));
  EXPECT_THAT(message(2), AllOf(HasSubstr("t.csv:4:3"), HasSubstr("found 'NaN', expected a finite number"),
                                HasSubstr("does not invent one")));
  EXPECT_THAT(message(3), AllOf(HasSubstr("t.csv:5:3"), HasSubstr("'-Infinity'"), HasSubstr("finite")));
  EXPECT_THAT(message(4), AllOf(HasSubstr("t.csv:6:3"), HasSubstr("'1e999'")));
  EXPECT_TRUE(std::isnan(table.RealOrNaN(2, 1)));
  EXPECT_THROW(table.RealOrNaN(3, 1), BadInput);
}

TEST(CsvTable, IntegerCellsMustBeWholeNumbers) {
  const CsvTable table = Parse("Packet number\n12\n12.5\n");
  EXPECT_EQ(table.Integer(0, 0), 12);
  EXPECT_THROW(table.Integer(1, 0), BadInput);
}

TEST(CsvTable, ReadFileNamesTheFileInEveryMessage) {
  const testing::ScratchDir dir("csv_table");
  std::vector<std::string> warnings;
  const auto file = dir.Write("x.csv", "a,b\n1,2\n");
  EXPECT_EQ(CsvTable::ReadFile(file, warnings).name(), file.string());
  try {
    CsvTable::ReadFile(dir / "missing.csv", warnings);
    FAIL() << "no exception";
  } catch (const BadInput& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("missing.csv"), HasSubstr("cannot be opened")));
  }
  EXPECT_THROW(CsvTable::ReadFile(dir.path(), warnings), BadInput);
}


// ---- RFC 4180 quoting

TEST(CsvTableQuoting, QuotedHeaderCellsAreReadWithoutTheirQuotes) {
  const CsvTable table = Parse("\"Time (s)\",\"Gyroscope x (rad/s)\"\n1.5E-2,\"-0.25\"\n");
  ASSERT_EQ(table.column_count(), 2u);
  EXPECT_EQ(table.header()[0], "Time (s)");
  EXPECT_EQ(table.header()[1], "Gyroscope x (rad/s)");
  EXPECT_DOUBLE_EQ(table.Real(0, 1), -0.25);
}

TEST(CsvTableQuoting, SeparatorsInsideQuotesAreTextAndDoubledQuotesAreOneQuote) {
  const CsvTable table = Parse("\"a, b\",\"say \"\"hi\"\"\",c\n1,2,3\n");
  ASSERT_EQ(table.column_count(), 3u);
  EXPECT_EQ(table.header()[0], "a, b");
  EXPECT_EQ(table.header()[1], "say \"hi\"");
  EXPECT_EQ(table.header()[2], "c");
  EXPECT_EQ(table.delimiter(), ',');
}

TEST(CsvTableQuoting, TheSeparatorIsCountedOutsideQuotes) {
  // Three commas inside the quotes, two semicolons outside: a ';'-file.
  const CsvTable table = Parse("\"a,b,c,d\";x;y\n1;2;3\n");
  EXPECT_EQ(table.delimiter(), ';');
  EXPECT_EQ(table.header()[0], "a,b,c,d");
}

TEST(CsvTableQuoting, SpacesAroundAQuotedFieldAreTrimmedAndInsideKept) {
  const CsvTable table = Parse("  \" a \" ,b\n1,2\n");
  EXPECT_EQ(table.header()[0], " a ");
}

TEST(CsvTableQuoting, AnUnterminatedQuoteIsAnErrorAtItsLineAndColumn) {
  EXPECT_THAT(ParseError("a,b\n1,\"2\n"), HasSubstr("t.csv:2:3:"));
  EXPECT_THAT(ParseError("a,b\n1,\"2\n"), HasSubstr("does not end on this line"));
}

TEST(CsvTableQuoting, TextAfterAClosingQuoteIsAnErrorAtItsLineAndColumn) {
  EXPECT_THAT(ParseError("\"a\"x,b\n1,2\n"), HasSubstr("t.csv:1:4:"));
  EXPECT_THAT(ParseError("a,b\n1,2\"3\n"), HasSubstr("t.csv:2:4:"));
}

}  // namespace
}  // namespace rockfit::io
