#include "rockfit/io/recording.hpp"

#include <utility>

#include <gtest/gtest.h>

namespace rockfit::io {
namespace {

TEST(Recording, DurationIsLastMinusFirstSampleTime) {
  Recording recording;
  EXPECT_EQ(recording.duration_s(), 0.0);
  recording.t_s = {0.0, 0.5, 1.25};
  EXPECT_EQ(recording.size(), 3u);
  EXPECT_DOUBLE_EQ(recording.duration_s(), 1.25);
  EXPECT_FALSE(recording.has_euler());
  EXPECT_FALSE(recording.has_accel());
  EXPECT_EQ(recording.mounting, "identity");
}

TEST(Recording, RateSourcesReadBackFromTheirNames) {
  const std::pair<RateSource, const char*> sources[] = {{RateSource::kOption, "option"},
                                                        {RateSource::kManifest, "manifest"},
                                                        {RateSource::kRegisters, "registers"},
                                                        {RateSource::kTimestamps, "timestamps"},
                                                        {RateSource::kFile, "file"}};
  for (const auto& [source, name] : sources) {
    EXPECT_STREQ(ToString(source), name);
    RateSource parsed = source == RateSource::kOption ? RateSource::kFile : RateSource::kOption;
    ASSERT_TRUE(FromString(name, &parsed)) << name;
    EXPECT_EQ(parsed, source) << name;
  }
  RateSource unchanged = RateSource::kManifest;
  for (const char* text : {"", "Option", "rate", "--rate", "timestamps "}) {
    EXPECT_FALSE(FromString(text, &unchanged)) << "'" << text << "'";
    EXPECT_EQ(unchanged, RateSource::kManifest);
  }
}

}  // namespace
}  // namespace rockfit::io
