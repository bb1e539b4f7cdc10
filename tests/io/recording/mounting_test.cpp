#include "rockfit/io/mounting.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::io {
namespace {

using ::testing::HasSubstr;

std::string ParseError(const std::string& text) {
  try {
    Mounting::Parse(text);
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "";
}

TEST(Mounting, DefaultAndIdentityLeaveVectorsAlone) {
  const Eigen::Vector3d v(1, 2, 3);
  EXPECT_TRUE(Mounting().ToBlock(v).isApprox(v));
  EXPECT_TRUE(Mounting::Parse("identity").is_identity());
  EXPECT_TRUE(Mounting::Parse("x,y,z").is_identity());
  EXPECT_TRUE(Mounting::Parse("").is_identity());
}

TEST(Mounting, PermutationEntryNamesTheSensorAxisAlongEachBlockAxis) {
  // Block x = sensor y, block y = −sensor x, block z = sensor z: the IMU turned by −90° about z.
  const Mounting mounting = Mounting::Parse(" y , -X, z");
  EXPECT_EQ(mounting.text(), "y,-x,z");
  const Eigen::Vector3d w_S(1, 2, 3);
  EXPECT_TRUE(mounting.ToBlock(w_S).isApprox(Eigen::Vector3d(2, -1, 3), 1e-15));
  Eigen::Matrix3d R_BS;
  R_BS << 0, 1, 0, -1, 0, 0, 0, 0, 1;
  EXPECT_TRUE(mounting.R_BS().isApprox(R_BS, 1e-15));
}

TEST(Mounting, UpsideDownIsARotationByPiAboutX) {
  const Mounting mounting = Mounting::Parse("x,-y,-z");
  EXPECT_TRUE(mounting.ToBlock({1, 2, 3}).isApprox(Eigen::Vector3d(1, -2, -3), 1e-15));
}

TEST(Mounting, BlockAttitudeIsSensorAttitudeTimesTheInverseMounting) {
  const Mounting mounting = Mounting::Parse("y,-x,z");
  const Eigen::Quaterniond q_WS(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
  const Eigen::Matrix3d R_WB = mounting.BlockAttitude(q_WS).toRotationMatrix();
  EXPECT_TRUE(R_WB.isApprox(q_WS.toRotationMatrix() * mounting.R_BS().transpose(), 1e-14));
  // A vector fixed in the block has the same world direction whichever frame it is written in.
  const Eigen::Vector3d v_S(0.2, -0.5, 0.9);
  EXPECT_TRUE((R_WB * mounting.ToBlock(v_S)).isApprox(q_WS * v_S, 1e-14));
}

TEST(Mounting, QuaternionFormIsQbsScalarFirst) {
  const Mounting mounting = Mounting::Parse("0.7071068,0,0,0.7071068");  // +90° about z
  EXPECT_TRUE(mounting.ToBlock({1, 0, 0}).isApprox(Eigen::Vector3d(0, 1, 0), 1e-6));
  EXPECT_THAT(ParseError("1,0,0,0.5"), HasSubstr("norm 1.11803"));
  EXPECT_THAT(ParseError("1,0,a,0"), HasSubstr("'a' is not a finite number"));
}

TEST(Mounting, RefusesMirrorImagesRepeatsAndNonsense) {
  EXPECT_THAT(ParseError("x,y,-z"), AllOf(HasSubstr("mirror image"), HasSubstr("'x,y,z'")));
  EXPECT_THAT(ParseError("-x,-y,-z"), HasSubstr("mirror image"));
  EXPECT_THAT(ParseError("x,x,z"), HasSubstr("sensor axis x appears twice"));
  EXPECT_THAT(ParseError("x,w,z"), HasSubstr("entry 2 is 'w'"));
  EXPECT_THAT(ParseError("x,y"), HasSubstr("found 2 comma-separated entries"));
  EXPECT_THROW(Mounting::FromRotation(2.0 * Eigen::Matrix3d::Identity()), InvalidArgument);
  EXPECT_THROW(Mounting::FromRotation(-Eigen::Matrix3d::Identity()), InvalidArgument);
}

}  // namespace
}  // namespace rockfit::io
