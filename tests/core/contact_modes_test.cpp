// Guards of the simulator's continuous modes: what they measure, where they change sign, and that their
// rates are the time derivatives of their values.
#include "detail/contact_modes.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "dop853.hpp"

namespace rockfit::core::detail {
namespace {

constexpr double kG = 9.81;

Block TestBlock() { return Block::FromDensity(0.05, 0.03, 0.2, 2692.0); }

TEST(VertexMode, GuardsOfTheFlatBlockAreZeroHeightsAndPositiveMargins) {
  const Block block = TestBlock();
  const VertexMode mode(block, 3, kG);
  EXPECT_EQ(mode.GuardVertex(VertexMode::kTouchNext), 4);
  EXPECT_EQ(mode.GuardVertex(VertexMode::kTouchPrevious), 2);
  const VertexMode::State flat = VertexDynamics::MakeState(Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero());
  EXPECT_NEAR(mode.Guard(VertexMode::kTouchNext, flat).value, 0.0, 1e-17);
  EXPECT_NEAR(mode.Guard(VertexMode::kTouchPrevious, flat).value, 0.0, 1e-17);
  EXPECT_GT(mode.Guard(VertexMode::kOverNext, flat).value, 0.0);
  EXPECT_GT(mode.Guard(VertexMode::kOverPrevious, flat).value, 0.0);
  EXPECT_EQ(mode.mode().ToString(), "V3");
}

TEST(VertexMode, OverturnGuardVanishesWithTheComAboveTheEdgeLine) {
  // Tilted about the edge V3V4 (the y direction at x = +b1) until the COM is straight above it: the guard of
  // the vertical plane through V3 along V3V4 is zero, and negative beyond.
  const Block block = TestBlock();
  const VertexMode mode(block, 3, kG);
  const double theta_c = std::atan(block.b1() / block.h());
  for (double extra : {-0.01, 0.0, 0.01}) {
    const Eigen::Quaterniond q(Eigen::AngleAxisd(theta_c + extra, Eigen::Vector3d::UnitY()));
    const VertexMode::State y = VertexDynamics::MakeState(q, Eigen::Vector3d::Zero());
    const double g = mode.Guard(VertexMode::kOverNext, y).value;
    if (extra == 0.0) {
      EXPECT_NEAR(g, 0.0, 1e-15);
    } else {
      EXPECT_EQ(g > 0.0, extra < 0.0) << "extra tilt " << extra << ", guard " << g;
    }
    EXPECT_GT(mode.Guard(VertexMode::kOverPrevious, y).value, 0.0);  // not past the side edge V2V3
  }
}

TEST(VertexMode, GuardRatesAreTheDerivativesOfTheGuards) {
  const Block block = TestBlock();
  const VertexMode mode(block, 3, kG);
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.1, Eigen::Vector3d(0.2, 1.0, 0.0).normalized()));
  const VertexMode::State y0 = VertexDynamics::MakeState(q, Eigen::Vector3d(0.3, -1.0, 0.4));
  Dop853<7> integrator(Dop853Options{});
  integrator.Reset(mode, 0.0, y0);
  ASSERT_EQ(integrator.Step(mode, 0.01), StepStatus::kOk);
  integrator.PrepareDense(mode);
  const double t = 0.5 * integrator.t();
  const double dt = 1e-6;
  VertexMode::State y, y_plus, y_minus;
  integrator.Interpolate(t, &y);
  integrator.Interpolate(t + dt, &y_plus);
  integrator.Interpolate(t - dt, &y_minus);
  for (int g = 0; g < VertexMode::kNumGuards; ++g) {
    const double numeric = (mode.Guard(g, y_plus).value - mode.Guard(g, y_minus).value) / (2.0 * dt);
    EXPECT_NEAR(mode.Guard(g, y).rate, numeric, 1e-8) << "guard " << g;
  }
}

TEST(VertexMode, ProjectRenormalisesTheQuaternion) {
  VertexMode::State y;
  y << 2.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0;
  VertexMode::Project(&y);
  EXPECT_NEAR(y.head<4>().norm(), 1.0, 1e-15);
  EXPECT_EQ(y.tail<3>(), Eigen::Vector3d(1.0, 2.0, 3.0));
}

TEST(EdgeMode, GuardsAreTheTiltAndTheOverturnMarginWithTheirRates) {
  const Block block = TestBlock();
  const EdgeMode mode(block, 1, 2, Eigen::Quaterniond::Identity(), kG);
  EXPECT_EQ(mode.mode().ToString(), "V1V2");
  const EdgeMode::State y(0.1, -0.7);
  EXPECT_EQ(mode.Guard(EdgeMode::kFlat, y).value, 0.1);
  EXPECT_EQ(mode.Guard(EdgeMode::kFlat, y).rate, -0.7);
  const double margin = block.b1() * std::cos(0.1) - block.h() * std::sin(0.1);
  EXPECT_NEAR(mode.Guard(EdgeMode::kOver, y).value, margin, 1e-16);
  const double dpsi = 1e-6;
  const double numeric = (mode.Guard(EdgeMode::kOver, {0.1 + dpsi, -0.7}).value -
                          mode.Guard(EdgeMode::kOver, {0.1 - dpsi, -0.7}).value) / (2.0 * dpsi) * -0.7;
  EXPECT_NEAR(mode.Guard(EdgeMode::kOver, y).rate, numeric, 1e-9);
  // The attitude is the yaw times the tilt about the edge.
  EXPECT_NEAR(mode.Attitude(y).angularDistance(Eigen::Quaterniond(Eigen::AngleAxisd(-0.1, Eigen::Vector3d::UnitY()))),
              0.0, 1e-15);
}

// The Edge mode's Euler angles are (yaw, ±ψ, 0) or (yaw, 0, ±ψ) without conversion; they agree with the general
// conversion of its attitude for every base edge, yaws of both signs and tilts on both sides of zero.
TEST(EdgeMode, EulerAnglesWithoutConversionMatchTheGeneralConversion) {
  const Block block = TestBlock();
  constexpr double kTol_rad = 1e-14;  // the round-off of the conversion's atan2/asin
  for (int i = 1; i <= 4; ++i) {
    for (int order = 0; order < 2; ++order) {
      const int a = order == 0 ? i : Block::WrapVertex(i + 1), b = order == 0 ? Block::WrapVertex(i + 1) : i;
      for (double yaw : {0.0, 0.7, -2.9, 3.1}) {
        const EdgeMode mode(block, a, b, YawQuaternion(yaw), kG);
        for (double psi : {0.0, 0.05, 0.12, -0.03}) {
          const EdgeMode::State y(psi, 0.4);
          const Eigen::Quaterniond q_WB = CanonicalQuaternion(mode.Attitude(y));
          const Eigen::Vector3d expected = EulerZyxFromQuaternion(q_WB);
          const Eigen::Vector3d euler = mode.EulerZyx(q_WB, y);
          EXPECT_LT((euler - expected).cwiseAbs().maxCoeff(), kTol_rad)
              << "V" << a << "V" << b << " yaw " << yaw << " psi " << psi << ": " << euler.transpose() << " vs "
              << expected.transpose();
        }
      }
    }
  }
}

}  // namespace
}  // namespace rockfit::core::detail
