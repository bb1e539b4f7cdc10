#include "rockfit/io/peer_at2.hpp"

#include <cmath>
#include <limits>
#include <map>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"
#include "test_paths.hpp"

namespace rockfit::io {
namespace {

std::string Message(const std::string& text) {
  try {
    ParsePeerAt2(text, "rec.AT2");
  } catch (const BadInput& e) {
    return e.what();
  }
  return "";
}

TEST(PeerAt2, ReadsPeerHeaderWithUnitAndENotationWithoutLeadingZero) {
  const PeerRecord r = ParsePeerAt2(
      "PEER STRONG MOTION DATABASE RECORD\nEVENT\nACCELERATION TIME HISTORY IN UNITS OF G\nNPTS=  7, DT= .01000 SEC\n"
      "   .1181069E-02   .1366453E-02   .9006674E-03  -.6490293E-04  -.1011537E-03\n  -.1199571E-03  -.1184308E-03\n",
      "rec.AT2");
  EXPECT_EQ(r.npts, 7u);
  EXPECT_EQ(r.dt_s, 0.01);
  ASSERT_EQ(r.accel_g.size(), 7u);
  EXPECT_EQ(r.accel_g[3], -.6490293E-04);
  EXPECT_EQ(r.header_lines.size(), 3u);
}

TEST(PeerAt2, ReadsLowerCaseStepWithoutUnitAndCrCrLfLineEnds) {
  const PeerRecord r = ParsePeerAt2("A\r\r\nB\r\r\nC\r\r\nNPTS=  3, dt=  .00500\r\r\n   .1E-01  -.2E-01   .3E-01\r\r\n", "rec.AT2");
  EXPECT_EQ(r.dt_s, 0.005);
  EXPECT_EQ(r.accel_g[1], -0.02);
}

TEST(PeerAt2, ReadsFixedWidthColumnsEvenWhenNegativeValuesTouch) {
  // 8F10.5: a value of ten characters touches the one before it.
  const PeerRecord r = ParsePeerAt2("free text\nmore\nunits (g)\nNPTS=  4, DT= .02000 SEC\n   0.00630-123.45678   0.00099  -0.00128\n",
                                    "rec.AT2");
  ASSERT_EQ(r.accel_g.size(), 4u);
  EXPECT_EQ(r.accel_g[0], 0.0063);
  EXPECT_EQ(r.accel_g[1], -123.45678);
  EXPECT_EQ(r.accel_g[3], -0.00128);
}

TEST(PeerAt2, ReadsTheNgaFormWithNumbersFirst) {
  const PeerRecord r = ParsePeerAt2("a\nb\nc\n    3   0.0050   NPTS, DT\n 1.0 2.0 3.0\n", "rec.AT2");
  EXPECT_EQ(r.npts, 3u);
  EXPECT_EQ(r.dt_s, 0.005);
}

TEST(PeerAt2, WrongCountAgainstNptsIsABadFileNamingTheLine) {
  const std::string fewer = Message("a\nb\nc\nNPTS=  4, DT= .01 SEC\n .1 .2 .3\n");
  EXPECT_NE(fewer.find("rec.AT2:5"), std::string::npos) << fewer;
  EXPECT_NE(fewer.find("3 values"), std::string::npos) << fewer;
  EXPECT_NE(fewer.find("NPTS = 4"), std::string::npos) << fewer;
  const std::string more = Message("a\nb\nc\nNPTS=  2, DT= .01 SEC\n .1 .2 .3\n");
  EXPECT_NE(more.find("rec.AT2:5:8"), std::string::npos) << more;
}

TEST(PeerAt2, BadValuesAndHeadersNameFileLineAndColumn) {
  const std::string comma = Message("a\nb\nc\nNPTS=  2, DT= .01 SEC\n  0,1  0.2\n");
  EXPECT_NE(comma.find("rec.AT2:5:3"), std::string::npos) << comma;
  EXPECT_NE(Message("a\nb\nc\nNPTS=  2, DT= .01 SEC\n  nan  0.2\n").find("rec.AT2:5:3"), std::string::npos);
  EXPECT_NE(Message("a\nb\nc\nNPTS=  x2, DT= .01 SEC\n  1  0.2\n").find("rec.AT2:4"), std::string::npos);
  EXPECT_NE(Message("a\nb\nc\nNPTS=  2, DT= -.01 SEC\n  1  0.2\n").find("positive time step"), std::string::npos);
  EXPECT_NE(Message("just\nsome\nnumbers\n1 2 3\n").find("NPTS"), std::string::npos);
}

TEST(PeerAt2, ValueThatOverflowsInSiAndNptsAboveTheLimitNameFileAndLine) {
  const std::string big = Message("a\nb\nc\nNPTS=  2, DT= .01 SEC\n  0.1  1e308\n");
  EXPECT_NE(big.find("rec.AT2:5:8: acceleration value 2"), std::string::npos) << big;
  const std::string npts = Message("a\nb\nc\nNPTS=  10000001, DT= .01 SEC\n  0.1  0.2\n");
  EXPECT_NE(npts.find("rec.AT2:4"), std::string::npos) << npts;
  EXPECT_NE(npts.find("at most 10000000 points"), std::string::npos) << npts;
}

TEST(PeerAt2, WriterRefusesWhatItCannotReadBackAndWritesFineStepsInFull) {
  PeerRecord r;
  r.dt_s = 0.005;
  r.accel_g = {0.0, std::nan("")};
  EXPECT_THROW(FormatPeerAt2(r), InvalidArgument);
  r.accel_g = {0.0, 1e308};
  EXPECT_THROW(FormatPeerAt2(r), InvalidArgument);
  r.accel_g = {0.0};
  EXPECT_THROW(FormatPeerAt2(r), InvalidArgument);
  r.accel_g = {0.0, 0.1};
  r.dt_s = std::numeric_limits<double>::infinity();
  EXPECT_THROW(FormatPeerAt2(r), InvalidArgument);
  r.dt_s = 1.25e-7;
  EXPECT_DOUBLE_EQ(ParsePeerAt2(FormatPeerAt2(r), "w.AT2").dt_s, 1.25e-7);
  r.dt_s = 0.005;
  EXPECT_NE(FormatPeerAt2(r).find("DT= .00500 SEC"), std::string::npos);
}

TEST(PeerAt2, WrittenRecordsReadBackExactlyToSevenDigits) {
  PeerRecord r;
  r.header_lines = {"one", "two", "three"};
  r.dt_s = 0.005;
  r.accel_g = {0.0, 0.1234567, -0.000987654321, 1.5, -0.99999996, 3e-9};
  r.npts = r.accel_g.size();
  const PeerRecord back = ParsePeerAt2(FormatPeerAt2(r), "written.AT2");
  ASSERT_EQ(back.npts, r.npts);
  EXPECT_EQ(back.dt_s, 0.005);
  for (std::size_t k = 0; k < r.npts; ++k) EXPECT_NEAR(back.accel_g[k], r.accel_g[k], 5e-8 * std::abs(r.accel_g[k]) + 1e-300);
}

TEST(PeerAt2, AllFiveSharedRealRecordsLoadWithTheirHeaderValues) {
  const std::filesystem::path dir = rockfit::testing::GroundMotionsDir();
  if (dir.empty()) GTEST_SKIP() << "the real ground-motion records beside the checkout are not present";
  struct Expected { std::size_t npts; double dt; double pga_g; };
  // NPTS and DT of the headers; the peaks as read (|a| max, g).
  const std::map<std::string, Expected> expected{{"A-ELC180.AT2", {4000, 0.01, 0.1301}},
                                                 {"ARL360.at2", {2000, 0.02, 0.3081}},
                                                 {"HAD-NS.AT2", {12000, 0.005, 0.0137}},
                                                 {"GCN-WE.AT2", {8192, 0.00244, 0.0739}},
                                                 {"elCentro.AT2", {1559, 0.02, 0.3188}}};
  for (const auto& [name, e] : expected) {
    const PeerRecord r = ReadPeerAt2(dir / name);
    EXPECT_EQ(r.npts, e.npts) << name;
    EXPECT_EQ(r.accel_g.size(), e.npts) << name;
    EXPECT_EQ(r.dt_s, e.dt) << name;
    EXPECT_NEAR(r.PeakAbs_g(), e.pga_g, 5e-5) << name;
  }
}

}  // namespace
}  // namespace rockfit::io
