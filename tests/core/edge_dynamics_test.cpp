// Rotation about a base edge (the Edge(i,j) mode): sign conventions of docs/design.md §2, the planar rocking
// equation, energy, yaw/tilt decomposition and the projection that keeps angular momentum about the edge.
#include "rockfit/core/edge_dynamics.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "rockfit/core/attitude.hpp"
#include "dop853.hpp"
#include "rockfit/core/errors.hpp"

namespace rockfit::core {
namespace {

constexpr double kG = 9.81;

Block TestBlock() { return Block::FromDensity(0.05, 0.03, 0.2, 2692.0); }

TEST(EdgeDynamics, ReleaseEdgeLiftsThePlusXSideWithNegativePitch) {
  const Block block = TestBlock();
  const EdgeDynamics edge(block, 1, 2, kG);
  const double alpha = 0.2;
  const Eigen::Quaterniond q = edge.Tilt(alpha);
  EXPECT_NEAR(EulerZyxFromQuaternion(q)[1], -alpha, 1e-15);
  EXPECT_GT(edge.PointHeight({alpha, 0.0}, block.p_BV_B(3)), 0.0);
  EXPECT_NEAR(edge.PointHeight({alpha, 0.0}, block.p_BV_B(1)), 0.0, 1e-17);
  // Falling back (ψ̇ < 0) turns about +y in B.
  const Eigen::Vector3d w_B = edge.AngularVelocity_B({alpha, -1.0});
  EXPECT_NEAR((w_B - Eigen::Vector3d(0.0, 1.0, 0.0)).norm(), 0.0, 1e-15);
}

TEST(EdgeDynamics, GeometryOfTheReleaseAndTheSideEdges) {
  const Block block = TestBlock();
  const EdgeDynamics front(block, 1, 2, kG);
  EXPECT_NEAR(front.critical_angle_rad(), std::atan(block.b1() / block.h()), 1e-15);
  const double R2 = block.b1() * block.b1() + block.h() * block.h();
  EXPECT_NEAR(front.inertia_kg_m2(), block.inertia_C_B()(1, 1) + block.mass() * R2, 1e-15);
  const EdgeDynamics side(block, 2, 3, kG);
  EXPECT_NEAR(side.critical_angle_rad(), std::atan(block.b2() / block.h()), 1e-15);
  EXPECT_NEAR(side.inertia_kg_m2(),
              block.inertia_C_B()(0, 0) + block.mass() * (block.b2() * block.b2() + block.h() * block.h()), 1e-15);
  EXPECT_THROW(EdgeDynamics(block, 1, 3, kG), InvalidArgument);
}

TEST(EdgeDynamics, AccelerationIsThePlanarRockingEquation) {
  // J ψ̈ = −m g R sin(θ_c − ψ).
  const Block block = TestBlock();
  const EdgeDynamics edge(block, 3, 4, kG);
  for (double psi : {0.0, 0.1, 0.2, 0.3}) {
    EdgeDynamics::State dydt;
    edge(0.0, {psi, 0.4}, dydt);
    const double expected =
        -block.mass() * kG * edge.arm_m() * std::sin(edge.critical_angle_rad() - psi) / edge.inertia_kg_m2();
    EXPECT_NEAR(dydt[1], expected, 1e-13);
    EXPECT_EQ(dydt[0], 0.4);
  }
}

TEST(EdgeDynamics, ConservesEnergyAlongAFall) {
  const Block block = TestBlock();
  const EdgeDynamics edge(block, 1, 2, kG);
  Dop853<2> integrator(Dop853Options{});
  const EdgeDynamics::State y0(0.2, 0.0);
  integrator.Reset(edge, 0.0, y0);
  while (integrator.t() < 0.2) ASSERT_EQ(integrator.Step(edge, 0.2), StepStatus::kOk);
  EXPECT_NEAR(edge.Energy(integrator.y()) / edge.Energy(y0) - 1.0, 0.0, 1e-13);
}

TEST(EdgeDynamics, DecomposeInvertsYawTimesTilt) {
  const Block block = TestBlock();
  for (int i = 1; i <= 4; ++i) {
    const EdgeDynamics edge(block, i, i + 1, kG);
    const Eigen::Quaterniond q_yaw = YawQuaternion(0.7);
    Eigen::Quaterniond yaw_back;
    double psi_back = 0.0;
    edge.Decompose(q_yaw * edge.Tilt(0.13), &yaw_back, &psi_back);
    EXPECT_NEAR(psi_back, 0.13, 1e-14);
    EXPECT_NEAR(yaw_back.angularDistance(q_yaw), 0.0, 1e-14);
  }
}

TEST(EdgeDynamics, ProjectionKeepsAngularMomentumAboutTheEdgeAndLosesEnergy) {
  const Block block = TestBlock();
  const EdgeDynamics edge(block, 3, 4, kG);
  // A rotation about V3 with components off the edge axis.
  const Eigen::Vector3d w_B(0.4, -1.1, 0.05);
  const double from_v3 = edge.ProjectAngularVelocity(w_B, block.p_BV_B(3));
  const Eigen::Vector3d c3 = block.p_BC_B() - block.p_BV_B(3);
  const Eigen::Matrix3d J3 = InertiaAboutPoint(block, block.p_BV_B(3));
  // Angular momentum about the edge line before (rotation about V3) and after (rotation about the edge).
  EXPECT_NEAR(edge.axis_B().dot(J3 * w_B), edge.inertia_kg_m2() * from_v3, 1e-15);
  const double energy_before = 0.5 * w_B.dot(J3 * w_B);
  const double energy_after = 0.5 * edge.inertia_kg_m2() * from_v3 * from_v3;
  EXPECT_LT(energy_after, energy_before);
  // A rotation that already is about the edge is unchanged.
  EXPECT_NEAR(edge.ProjectAngularVelocity(-0.8 * edge.axis_B(), block.p_BV_B(4)), -0.8, 1e-15);
  (void)c3;
}

TEST(EdgeDynamics, NormalForceIsTheWeightAtTheBalancePoint) {
  const Block block = TestBlock();
  const EdgeDynamics edge(block, 1, 2, kG);
  const EdgeDynamics::State y(edge.critical_angle_rad(), 0.0);
  EdgeDynamics::State dydt;
  edge(0.0, y, dydt);
  const ContactForce force = edge.Force(y, dydt, Eigen::Quaterniond::Identity());
  EXPECT_NEAR(force.normal_N, block.mass() * kG, 1e-12);
  EXPECT_NEAR(force.tangential_N, 0.0, 1e-12);
  EXPECT_NEAR(edge.OverturnMargin(y), 0.0, 1e-15);
}

}  // namespace
}  // namespace rockfit::core
