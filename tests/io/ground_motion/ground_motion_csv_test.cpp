#include "rockfit/io/ground_motion_csv.hpp"

#include <fstream>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/core/ground_motion.hpp"
#include "scratch_dir.hpp"

namespace rockfit::io {
namespace {

std::filesystem::path Write(const std::filesystem::path& dir, const std::string& name, const std::string& text) {
  const std::filesystem::path p = dir / name;
  std::ofstream(p) << text;
  return p;
}

TEST(GroundMotionCsv, ReadsTimeAndThreeNamedComponentsInG) {
  rockfit::testing::ScratchDir dir("gm_csv");
  const auto p = Write(dir.path(), "a.csv", "time [s],z,x,y\n0,0.1,0.2,0.3\n0.01,0,1,-1\n0.02,0,0,0\n");
  const GroundMotionComponents c = ReadGroundMotionCsv(p, {});
  EXPECT_NEAR(c.dt_s, 0.01, 1e-15);
  ASSERT_EQ(c.roles.size(), 3u);
  EXPECT_EQ(c.roles[0], "v");
  EXPECT_EQ(c.roles[1], "h1");
  EXPECT_DOUBLE_EQ(c.accel_m_s2[1][1], core::kRecordGravity);
}

TEST(GroundMotionCsv, WithoutTimeColumnNeedsTheStep) {
  rockfit::testing::ScratchDir dir("gm_csv");
  const auto p = Write(dir.path(), "b.csv", "a1\n1\n2\n");
  EXPECT_THROW(ReadGroundMotionCsv(p, {}), BadInput);
  CsvGroundMotionOptions o;
  o.dt_s = 0.02;
  o.unit = GroundAccelerationUnit::kCentimetrePerSecond2;
  const GroundMotionComponents c = ReadGroundMotionCsv(p, o);
  EXPECT_EQ(c.roles[0], "h1");
  EXPECT_DOUBLE_EQ(c.accel_m_s2[0][1], 0.02);
}

TEST(GroundMotionCsv, NonUniformTimeIsABadFileNamingTheCell) {
  rockfit::testing::ScratchDir dir("gm_csv");
  const auto p = Write(dir.path(), "c.csv", "t,x\n0,1\n0.01,2\n0.03,3\n");
  try {
    ReadGroundMotionCsv(p, {});
    FAIL();
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("c.csv:4:1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rockfit::io
