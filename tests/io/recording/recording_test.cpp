#include "rockfit/io/recording.hpp"

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

}  // namespace
}  // namespace rockfit::io
