#include "ximu/ximu_gui_file_set.hpp"

#include <gtest/gtest.h>

#include "scratch_dir.hpp"

namespace rockfit::io {
namespace {

TEST(XimuGuiBaseName, StripsAKnownTypeSuffixOnly) {
  EXPECT_EQ(XimuGuiBaseName("LoggedData_EulerAngles.csv"), "LoggedData");
  EXPECT_EQ(XimuGuiBaseName("my_trial_2_calinertialandmag.CSV"), "my_trial_2");
  EXPECT_EQ(XimuGuiBaseName("00000_CalInertialMagnetic.csv"), "00000");  // API v7–v11 name
  EXPECT_FALSE(XimuGuiBaseName("LoggedData_Gyro.csv"));
  EXPECT_FALSE(XimuGuiBaseName("_EulerAngles.csv"));
  EXPECT_FALSE(XimuGuiBaseName("Inertial.csv"));
}

TEST(XimuGuiFileSet, GroupsFilesByPrefixWhateverTheirCase) {
  const testing::ScratchDir dir("file_set");
  dir.Write("A_CalInertialAndMag.csv", "x");
  dir.Write("A_eulerangles.csv", "x");
  dir.Write("A_Registers.csv", "x");
  dir.Write("A_B_Quaternion.csv", "x");  // belongs to prefix "A_B"
  dir.Write("B_CalInertialMagnetic.csv", "x");
  const XimuGuiFileSet a = XimuGuiFileSet::Find(dir / "A");
  EXPECT_EQ(a.cal_inertial, dir / "A_CalInertialAndMag.csv");
  EXPECT_EQ(a.euler_angles, dir / "A_eulerangles.csv");
  EXPECT_TRUE(a.registers);
  EXPECT_FALSE(a.quaternion);
  EXPECT_EQ(a.all.size(), 3u);
  EXPECT_EQ(XimuGuiFileSet::Find(dir / "A_B").quaternion, dir / "A_B_Quaternion.csv");
  EXPECT_EQ(XimuGuiFileSet::Find(dir / "B").cal_inertial, dir / "B_CalInertialMagnetic.csv");
  EXPECT_EQ(XimuGuiBasesIn(dir.path()), (std::vector<std::string>{"A", "B"}));
}

}  // namespace
}  // namespace rockfit::io
