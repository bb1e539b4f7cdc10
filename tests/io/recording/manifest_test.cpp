#include "rockfit/io/manifest.hpp"

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/io/input_limits.hpp"
#include "scratch_dir.hpp"
#include "special_files.hpp"

namespace rockfit::io {
namespace {

const char* kGood = R"(# two blocks, three trials
[[blocks]]
id = "B3"
b1 = 0.05
b2 = 0.03
h = 0.2
density = 2692

[[blocks]]
id = "B8"
b1 = 0.05
b2 = 0.1
h = 0.2
mass = 10.77

[[trials]]
id = "B3-A-1"
block = "B3"
position = "A"
files = "raw/B3-A-1"
rate = 256
mounting = "x,-y,-z"
notes = "first release"

[[trials]]
id = "B3-B-1"
block = "B3"
position = "B"
files = "raw/B3-B-1"
format = "ximu-gui"

[[trials]]
id = "B8-A-1"
block = "B8"
position = "A"
files = "/data/x3/B8-A-1"
format = "ximu3"
)";

// The message of the BadInput thrown by parsing `text` as /campaign/m.toml.
std::string ErrorOf(const std::string& text) {
  try {
    ParseManifest(text, "/campaign/m.toml");
  } catch (const BadInput& e) {
    return e.what();
  }
  return "no error";
}

TEST(Manifest, ReadsBlocksAndTrialsWithPathsRelativeToTheManifest) {
  const Manifest m = ParseManifest(kGood, "/campaign/m.toml");
  ASSERT_EQ(m.blocks.size(), 2u);
  ASSERT_EQ(m.trials.size(), 3u);
  EXPECT_EQ(m.blocks[0].id, "B3");
  EXPECT_DOUBLE_EQ(*m.blocks[0].density_kg_m3, 2692.0);
  EXPECT_FALSE(m.blocks[0].mass_kg.has_value());
  EXPECT_DOUBLE_EQ(m.blocks[1].ToBlock().mass(), 10.77);
  EXPECT_DOUBLE_EQ(m.blocks[0].ToBlock().mass(), 8 * 2692.0 * 0.05 * 0.03 * 0.2);
  const TrialSpec& t = m.FindTrial("B3-A-1");
  EXPECT_EQ(t.block_id, "B3");
  EXPECT_EQ(t.position, "A");
  EXPECT_EQ(t.files, std::filesystem::path("/campaign/raw/B3-A-1"));
  EXPECT_EQ(t.files_as_written, "raw/B3-A-1");
  EXPECT_EQ(t.format, "auto");
  EXPECT_DOUBLE_EQ(*t.rate_hz, 256.0);
  EXPECT_EQ(t.mounting, "x,-y,-z");
  EXPECT_EQ(t.where.line, 16u);
  EXPECT_EQ(m.FindTrial("B3-B-1").format, "ximu-gui");
  EXPECT_FALSE(m.FindTrial("B3-B-1").rate_hz.has_value());
  EXPECT_EQ(m.FindTrial("B8-A-1").files, std::filesystem::path("/data/x3/B8-A-1"));
}

TEST(Manifest, UnknownKeyNamesLineColumnAndSuggestsTheKey) {
  std::string text = kGood;
  text.replace(text.find("rate = 256"), 10, "rat = 256");
  EXPECT_EQ(ErrorOf(text), "/campaign/m.toml:21:1: unknown key 'rat' in [[trials]] number 1 (did you mean 'rate'?); "
                           "allowed keys: id, block, position, files, format, rate, mounting, columns, notes");
}

TEST(Manifest, UnknownTopLevelKeyIsAnError) {
  const std::string message = ErrorOf(std::string("title = \"x\"\n") + kGood);
  EXPECT_NE(message.find("m.toml:1:1: unknown key 'title' in the manifest (top level)"), std::string::npos) << message;
}

TEST(Manifest, MissingKeyNamesTheTableAndTheKey) {
  std::string text = kGood;
  text.replace(text.find("position = \"B\"\n"), 15, "");
  const std::string message = ErrorOf(text);
  EXPECT_NE(message.find("m.toml:25:1: [[trials]] 'B3-B-1' has no 'position'"), std::string::npos) << message;
}

TEST(Manifest, UnknownBlockIdPointsAtTheValueAndListsTheKnownBlocks) {
  std::string text = kGood;
  text.replace(text.find("block = \"B8\""), 12, "block = \"B9\"");
  const std::string message = ErrorOf(text);
  EXPECT_NE(message.find("m.toml:34:9: [[trials]] 'B8-A-1' names block 'B9'"), std::string::npos) << message;
  EXPECT_NE(message.find("known blocks: B3, B8"), std::string::npos) << message;
}

TEST(Manifest, DuplicateIdsAreErrorsNamingTheFirstDefinition) {
  std::string text = kGood;
  text.replace(text.find("id = \"B3-B-1\""), 13, "id = \"B3-A-1\"");
  const std::string message = ErrorOf(text);
  EXPECT_NE(message.find("m.toml:26:6: duplicate trial id 'B3-A-1' (first defined at line 17)"), std::string::npos)
      << message;
  std::string blocks = kGood;
  blocks.replace(blocks.find("id = \"B8\""), 9, "id = \"B3\"");
  EXPECT_NE(ErrorOf(blocks).find("duplicate block id 'B3' (first defined at line 3)"), std::string::npos);
}

TEST(Manifest, DensityAndMassAreExclusiveAndSizesPositive) {
  std::string both = kGood;
  both.replace(both.find("density = 2692"), 14, "density = 2692\nmass = 1");
  EXPECT_NE(ErrorOf(both).find("needs exactly one of 'density' [kg/m³] or 'mass' [kg], not both"), std::string::npos);
  std::string negative = kGood;
  negative.replace(negative.find("b1 = 0.05"), 9, "b1 = -0.05");
  EXPECT_NE(ErrorOf(negative).find("m.toml:4:6: 'b1' in [[blocks]] 'B3' must be a positive number [m], got -0.05"),
            std::string::npos)
      << ErrorOf(negative);
  std::string text_size = kGood;
  text_size.replace(text_size.find("h = 0.2"), 7, "h = \"0.2\"");
  EXPECT_NE(ErrorOf(text_size).find("'h' in [[blocks]] 'B3' must be a number [m]"), std::string::npos);
}

TEST(Manifest, SyntaxErrorsCarryTomlsPosition) {
  const std::string message = ErrorOf("[[blocks]]\nid = \"B1\nb1 = 0.05\n");
  EXPECT_NE(message.find("/campaign/m.toml:2:"), std::string::npos) << message;
  EXPECT_NE(message.find("TOML syntax error"), std::string::npos) << message;
}

TEST(Manifest, UnknownFormatAndBadIdsAreRejected) {
  std::string text = kGood;
  text.replace(text.find("format = \"ximu3\""), 16, "format = \"ximu4\"");
  EXPECT_NE(ErrorOf(text).find("unknown format 'ximu4'; use one of auto, ximu-gui, ximu3, generic-csv, rockfit-hdf5"),
            std::string::npos);
  std::string slash = kGood;
  slash.replace(slash.find("id = \"B3-A-1\""), 13, "id = \"B3/A/1\"");
  EXPECT_NE(ErrorOf(slash).find("trial id 'B3/A/1' may only contain"), std::string::npos);
}

TEST(Manifest, BadMountingIsReportedAtItsPosition) {
  std::string text = kGood;
  text.replace(text.find("mounting = \"x,-y,-z\""), 20, "mounting = \"x,y,-z\"");
  const std::string message = ErrorOf(text);
  EXPECT_NE(message.find("m.toml:22:12: [[trials]] 'B3-A-1': "), std::string::npos) << message;
  EXPECT_NE(message.find("x,y,-z"), std::string::npos) << message;
}

TEST(Manifest, AutoMountingIsAcceptedAloneOrWithAStart) {
  for (const std::string mounting : {"auto", "auto:x,-y,-z"}) {
    std::string text = kGood;
    text.replace(text.find("mounting = \"x,-y,-z\""), 20, "mounting = \"" + mounting + "\"");
    EXPECT_EQ(ParseManifest(text, "/campaign/m.toml").FindTrial("B3-A-1").mounting, mounting);
  }
  std::string mirrored = kGood;
  mirrored.replace(mirrored.find("mounting = \"x,-y,-z\""), 20, "mounting = \"auto:x,y,-z\"");
  EXPECT_NE(ErrorOf(mirrored).find("m.toml:22:12:"), std::string::npos) << ErrorOf(mirrored);
}

TEST(Manifest, CsvIsAcceptedAsTheGenericCsvFormat) {
  std::string text = kGood;
  text.replace(text.find("format = \"ximu3\""), 16, "format = \"csv\"");
  EXPECT_EQ(ParseManifest(text, "/campaign/m.toml").FindTrial("B8-A-1").format, "csv");
}

TEST(Manifest, EmptyManifestAndMissingFileAreBadInput) {
  EXPECT_NE(ErrorOf("# nothing\n").find("defines no [[blocks]] and no [[trials]]"), std::string::npos);
  EXPECT_THROW(ReadManifest("/nonexistent/campaign.toml"), BadInput);
}

TEST(Manifest, DottedKeyOfFortyThousandPartsIsRefusedWithoutParsing) {
  std::string key = "a";
  for (int k = 1; k < 40000; ++k) key += ".a";
  const std::string message = ErrorOf(key + " = 1\n");
  EXPECT_NE(message.find("/campaign/m.toml:1:128: a dotted key or table name of more than 64 parts"),
            std::string::npos) << message;
  // Dots inside strings, comments and numbers are no key parts.
  std::string text = kGood;
  text += "# " + key + "\n";
  text.replace(text.find("files = \"raw/B3-B-1\""), 20, "files = \"" + key + "\"");
  EXPECT_EQ(ParseManifest(text, "/campaign/m.toml").trials.size(), 3u);
  EXPECT_NE(ErrorOf("[" + key + "]\n").find("more than 64 parts"), std::string::npos);
}

TEST(Manifest, MoreTrialsThanTheLimitAreRefusedAtTheFirstOneTooMany) {
  std::string text = "[[blocks]]\nid = \"b\"\nb1 = 0.05\nb2 = 0.03\nh = 0.2\ndensity = 2692\n";
  for (std::size_t k = 0; k <= kMaxManifestEntries; ++k) text += "[[trials]]\n";
  const std::string message = ErrorOf(text);
  EXPECT_NE(message.find(":100007:1: 100001 [[trials]] entries, more than the 100000"), std::string::npos) << message;
}

TEST(Manifest, NulInAStringIsRefusedAtItsPositionAndQuotedEscaped) {
  std::string text = kGood;
  text.replace(text.find("id = \"B3-B-1\""), 13, "id = \"B3\\u0000x\"");
  const std::string message = ErrorOf(text);
  EXPECT_NE(message.find("'id' in [[trials]] number 2 holds a NUL byte"), std::string::npos) << message;
  EXPECT_NE(message.find("'B3\\x00x'"), std::string::npos) << message;
}

TEST(Manifest, UnknownIdWithANulByteIsQuotedWhole) {
  const Manifest m = ParseManifest(kGood, "/campaign/m.toml");
  try {
    m.FindTrial(std::string("B3-A-1\0x", 8));
    FAIL();
  } catch (const BadInput& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("no trial 'B3-A-1\\x00x'; known trials: B3-A-1"), std::string::npos) << what;
  }
}

TEST(Manifest, DirectoryOrFifoIsBadInputNamingWhatItIs) {
  const testing::ScratchDir dir("manifest_special");
  try {
    ReadManifest(dir.path());
    FAIL();
  } catch (const BadInput& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("found a directory, expected a manifest (TOML)"), std::string::npos) << what;
  }
  ASSERT_TRUE(testing::MakeFifo(dir / "m.toml"));
  EXPECT_THROW(ReadManifest(dir / "m.toml"), BadInput);
}

TEST(Manifest, FindReportsKnownIds) {
  const Manifest m = ParseManifest(kGood, "/campaign/m.toml");
  try {
    m.FindBlock("B4");
    FAIL();
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("no block 'B4'; known blocks: B3, B8"), std::string::npos);
  }
}

TEST(Manifest, ReadsFromAFile) {
  const testing::ScratchDir dir("manifest");
  const Manifest m = ReadManifest(dir.Write("m.toml", kGood));
  EXPECT_EQ(m.FindTrial("B3-A-1").files, dir / "raw/B3-A-1");
}

TEST(Manifest, ATrialTakesItsColumnMapAndTheBlocksDefaultsForWhatItLeavesOut) {
  const std::string text = R"([[blocks]]
id = "P"
b1 = 0.05
b2 = 0.03
h = 0.2
density = 2692
format = "csv"
columns = "phyphox"
rate = 100
mounting = "x,-y,-z"

[[trials]]
id = "P-1"
block = "P"
position = "A"
files = "phone/Gyroscope.csv"

[[trials]]
id = "P-2"
block = "P"
position = "A"
files = "logger/log.csv"
format = "generic-csv"
columns = "time=ms@ms;gyro=gx,gy,gz@dps"
mounting = "x,y,z"
)";
  const Manifest m = ParseManifest(text, "/campaign/m.toml");
  const TrialSpec& p1 = m.FindTrial("P-1");
  EXPECT_EQ(p1.format, "csv");
  EXPECT_EQ(p1.columns, "phyphox");
  EXPECT_EQ(p1.rate_hz, 100.0);
  EXPECT_EQ(p1.mounting, "x,-y,-z");
  const TrialSpec& p2 = m.FindTrial("P-2");
  EXPECT_EQ(p2.format, "generic-csv");
  EXPECT_EQ(p2.columns, "time=ms@ms;gyro=gx,gy,gz@dps");
  EXPECT_EQ(p2.mounting, "x,y,z");
}

TEST(Manifest, ABadColumnMapIsReportedAtItsLineAndColumn) {
  const std::string text = std::string(kGood) + R"(
[[trials]]
id = "B3-C-1"
block = "B3"
position = "C"
files = "raw/c.csv"
columns = "gyro=a,b@rad/s"
)";
  const std::string message = ErrorOf(text);
  EXPECT_NE(message.find("m.toml:"), std::string::npos) << message;
  EXPECT_NE(message.find("gyro needs three column names"), std::string::npos) << message;
}

}  // namespace
}  // namespace rockfit::io
