// Rotation about a fixed body point (the Vertex(k) mode): the vertical in B and the right-hand side against
// Eigen's rotation matrix at quaternions off unit norm, inertia by direct integration over the box, agreement with an independent world-frame angular-momentum formulation, energy conservation, the
// contact force against the COM acceleration, and the edge-midpoint pivot against the 1-DOF edge model.
#include "rockfit/core/vertex_dynamics.hpp"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "dop853.hpp"
#include "rockfit/core/edge_dynamics.hpp"

namespace rockfit::core {
namespace {

constexpr double kG = 9.81;

Block TestBlock() { return Block::FromDensity(0.05, 0.03, 0.2, 2692.0); }

Dop853Options TightOptions() {
  Dop853Options options;
  options.rel_tol = 1e-13;
  options.abs_tol = 1e-15;
  return options;
}

template <int N, class Rhs>
Eigen::Matrix<double, N, 1> Integrate(const Rhs& rhs, const Eigen::Matrix<double, N, 1>& y0, double t_end) {
  Dop853<N> integrator(TightOptions());
  integrator.Reset(rhs, 0.0, y0);
  while (integrator.t() < t_end) EXPECT_EQ(integrator.Step(rhs, t_end), StepStatus::kOk);
  return integrator.y();
}

// Inertia of the homogeneous box [−b1,b1]×[−b2,b2]×[0,2h] about the body point P, by the defining
// integrals J = ρ∫(|r|²I − r rᵀ) dV with r = x − P, evaluated exactly (polynomials over a box).
Eigen::Matrix3d BoxInertiaByIntegration(const Block& block, const Eigen::Vector3d& P) {
  const Eigen::Vector3d lo(-block.b1() - P.x(), -block.b2() - P.y(), 0.0 - P.z());
  const Eigen::Vector3d hi(block.b1() - P.x(), block.b2() - P.y(), 2.0 * block.h() - P.z());
  const Eigen::Vector3d len = hi - lo;
  const double volume = len.prod();
  const double rho = block.mass() / volume;
  Eigen::Vector3d first, second;  // ∫x_i dx_i / len_i and ∫x_i² dx_i / len_i
  for (int i = 0; i < 3; ++i) {
    first[i] = (hi[i] * hi[i] - lo[i] * lo[i]) / (2.0 * len[i]);
    second[i] = (std::pow(hi[i], 3) - std::pow(lo[i], 3)) / (3.0 * len[i]);
  }
  Eigen::Matrix3d J;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (i == j) {
        J(i, i) = rho * volume * (second.sum() - second[i]);
      } else {
        J(i, j) = -rho * volume * first[i] * first[j];
      }
    }
  }
  return J;
}

// Quaternions off unit norm by up to 1e-5 relative (as DOP853's stages see them), from a fixed seed.
std::vector<VertexDynamics::State> NonUnitStates() {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> stretch(1.0 - 1e-5, 1.0 + 1e-5);
  std::vector<VertexDynamics::State> states;
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector4d q = Eigen::Vector4d(normal(rng), normal(rng), normal(rng), normal(rng)).normalized() *
                              stretch(rng);
    VertexDynamics::State y;
    y << q, 3.0 * normal(rng), 3.0 * normal(rng), 3.0 * normal(rng);
    states.push_back(y);
  }
  return states;
}

// Round-off of a few products of unit-size numbers, the vertical's components being of order one [1].
constexpr double kVerticalRoundOffTol = 1e-15;

TEST(VertexDynamics, UpInBodyPartsGiveTheVerticalOfEigensRotationMatrix) {
  for (const VertexDynamics::State& y : NonUnitStates()) {
    const Eigen::Matrix3d R_WB = Eigen::Quaterniond(y[0], y[1], y[2], y[3]).normalized().toRotationMatrix();
    const Eigen::Vector3d expected_B = R_WB.transpose() * Eigen::Vector3d::UnitZ();
    const VertexDynamics::UpParts up = VertexDynamics::UpInBodyParts(y);
    EXPECT_NEAR((up.scale * up.tilt_B + Eigen::Vector3d::UnitZ() - expected_B).norm(), 0.0, kVerticalRoundOffTol);
    EXPECT_NEAR((VertexDynamics::UpInBody(y) - expected_B).norm(), 0.0, kVerticalRoundOffTol);
  }
}

// Round-off of ẇ relative to its size: J_P⁻¹ amplifies the torques' round-off by its condition number (~10) [1].
constexpr double kAngularAccelerationRelTol = 1e-13;

// Round-off of q̇ = ½ q ⊗ (0, w) relative to its size: three products summed per component [1].
constexpr double kQuaternionRateRelTol = 1e-15;

TEST(VertexDynamics, RightHandSideIsEulersEquationsWithEigensRotationMatrix) {
  const Block block = TestBlock();
  for (int k = 1; k <= 4; ++k) {
    const VertexDynamics dynamics(block, k, kG);
    const Eigen::Matrix3d& J = dynamics.inertia_P_B();
    for (const VertexDynamics::State& y : NonUnitStates()) {
      const Eigen::Quaterniond q(y[0], y[1], y[2], y[3]);
      const Eigen::Vector3d up_B = q.normalized().toRotationMatrix().transpose() * Eigen::Vector3d::UnitZ();
      const Eigen::Vector3d w_B = y.tail<3>();
      const Eigen::Vector3d torque_B = dynamics.p_PC_B().cross(-block.mass() * kG * up_B);
      const Eigen::Vector3d expected_w_dot_B = J.lu().solve(torque_B - w_B.cross(J * w_B));
      const Eigen::Quaterniond expected_q_dot = q * Eigen::Quaterniond(0.0, w_B.x(), w_B.y(), w_B.z());
      VertexDynamics::State dydt;
      dynamics(0.0, y, dydt);
      EXPECT_NEAR((dydt.tail<3>() - expected_w_dot_B).norm() / expected_w_dot_B.norm(), 0.0,
                  kAngularAccelerationRelTol)
          << "V" << k;
      const Eigen::Vector4d expected_q_dot_wxyz =
          0.5 * Eigen::Vector4d(expected_q_dot.w(), expected_q_dot.x(), expected_q_dot.y(), expected_q_dot.z());
      EXPECT_NEAR((dydt.head<4>() - expected_q_dot_wxyz).norm() / expected_q_dot_wxyz.norm(), 0.0,
                  kQuaternionRateRelTol)
          << "V" << k;
    }
  }
}

TEST(VertexDynamics, InertiaAboutAVertexMatchesTheDefiningIntegral) {
  const Block block = TestBlock();
  for (int k = 1; k <= 4; ++k) {
    const Eigen::Matrix3d expected = BoxInertiaByIntegration(block, block.p_BV_B(k));
    const Eigen::Matrix3d J = VertexDynamics(block, k, kG).inertia_P_B();
    EXPECT_NEAR((J - expected).norm() / expected.norm(), 0.0, 1e-14) << "V" << k;
  }
}

// An asymmetric initial state: tilted about V3 with spin, so that all three components of w_B matter.
VertexDynamics::State SpinningState() {
  const Eigen::Quaterniond q = Eigen::Quaterniond(Eigen::AngleAxisd(0.15, Eigen::Vector3d(0.3, 1.0, 0.1).normalized()));
  return VertexDynamics::MakeState(q, Eigen::Vector3d(0.7, -1.3, 2.1));
}

// World-frame formulation about the pivot P: L̇_W = p_PC_W × (−m g e_z), ω_W = (R J_P Rᵀ)⁻¹ L_W, Ṙ = [ω_W]× R.
// State (R column-major, L_W): shares nothing with VertexDynamics but the block's mass and inertia.
struct WorldFrameRotation {
  Eigen::Matrix3d J_P_B;
  Eigen::Vector3d p_PC_B;
  double weight_N;
  void operator()(double, const Eigen::Matrix<double, 12, 1>& y, Eigen::Matrix<double, 12, 1>& dydt) const {
    const Eigen::Map<const Eigen::Matrix3d> R(y.data());
    const Eigen::Vector3d L_W = y.tail<3>();
    const Eigen::Matrix3d J_W = R * J_P_B * R.transpose();
    const Eigen::Vector3d w_W = J_W.ldlt().solve(L_W);
    Eigen::Matrix3d skew;
    skew << 0, -w_W.z(), w_W.y(), w_W.z(), 0, -w_W.x(), -w_W.y(), w_W.x(), 0;
    const Eigen::Matrix3d R_dot = skew * R;
    Eigen::Map<Eigen::Matrix3d>(dydt.data()) = R_dot;
    dydt.tail<3>() = (R * p_PC_B).cross(Eigen::Vector3d(0.0, 0.0, -weight_N));
  }
};

TEST(VertexDynamics, AgreesWithTheWorldFrameAngularMomentumFormulation) {
  const Block block = TestBlock();
  const VertexDynamics dynamics(block, 3, kG);
  const VertexDynamics::State y0 = SpinningState();
  const Eigen::Matrix3d R0 = VertexDynamics::Attitude(y0).toRotationMatrix();
  Eigen::Matrix<double, 12, 1> z0;
  Eigen::Map<Eigen::Matrix3d>(z0.data()) = R0;
  z0.tail<3>() = R0 * (dynamics.inertia_P_B() * VertexDynamics::AngularVelocity(y0));
  const WorldFrameRotation world{dynamics.inertia_P_B(), dynamics.p_PC_B(), block.mass() * kG};
  for (double t_end : {0.05, 0.2}) {
    const VertexDynamics::State y = Integrate<7>(dynamics, y0, t_end);
    const Eigen::Matrix<double, 12, 1> z = Integrate<12>(world, z0, t_end);
    const Eigen::Matrix3d R_world = Eigen::Map<const Eigen::Matrix3d>(z.data());
    const Eigen::Matrix3d R_body = VertexDynamics::Attitude(y).toRotationMatrix();
    EXPECT_NEAR((R_body - R_world).norm(), 0.0, 1e-10) << "t = " << t_end;
    const Eigen::Vector3d w_B_world = R_world.transpose() * (R_world * dynamics.inertia_P_B() * R_world.transpose())
                                                                .ldlt()
                                                                .solve(z.tail<3>());
    EXPECT_NEAR((VertexDynamics::AngularVelocity(y) - w_B_world).norm(), 0.0, 1e-9) << "t = " << t_end;
  }
}

TEST(VertexDynamics, ConservesEnergy) {
  const Block block = TestBlock();
  const VertexDynamics dynamics(block, 3, kG);
  const VertexDynamics::State y0 = SpinningState();
  const VertexDynamics::State y = Integrate<7>(dynamics, y0, 0.3);
  EXPECT_NEAR(dynamics.Energy(y) / dynamics.Energy(y0) - 1.0, 0.0, 1e-12);
}

TEST(VertexDynamics, ContactForceEqualsMassTimesComAccelerationPlusWeight) {
  const Block block = TestBlock();
  const VertexDynamics dynamics(block, 3, kG);
  const VertexDynamics::State y0 = SpinningState();
  // COM acceleration in W by a central second difference of p_PC_W(t) = R(t)·c.
  const double t = 0.1;
  const double dt = 1e-4;
  const auto com_W = [&](double time) {
    return (VertexDynamics::Attitude(Integrate<7>(dynamics, y0, time)) * dynamics.p_PC_B()).eval();
  };
  const Eigen::Vector3d a_C_W = (com_W(t + dt) - 2.0 * com_W(t) + com_W(t - dt)) / (dt * dt);
  const VertexDynamics::State y = Integrate<7>(dynamics, y0, t);
  VertexDynamics::State dydt;
  dynamics(t, y, dydt);
  const ContactForce force = dynamics.Force(y, dydt);
  const Eigen::Vector3d expected = block.mass() * (a_C_W + kG * Eigen::Vector3d::UnitZ());
  // The difference quotient carries an O(dt²) truncation and O(ε/dt²) round-off error.
  EXPECT_NEAR((force.F_W - expected).norm() / expected.norm(), 0.0, 1e-6);
  EXPECT_NEAR(force.normal_N, force.F_W.z(), 1e-12 * expected.norm());
  EXPECT_NEAR(force.tangential_N, force.F_W.head<2>().norm(), 1e-12 * expected.norm());
}

TEST(VertexDynamics, StaticBalanceOverThePivotNeedsExactlyTheWeight) {
  const Block block = TestBlock();
  const VertexDynamics dynamics(block, 3, kG);
  // Rotate so that the COM lies straight above V3: c = p_PC_B goes to the vertical.
  const Eigen::Vector3d c = dynamics.p_PC_B();
  const Eigen::Quaterniond q = Eigen::Quaterniond::FromTwoVectors(c, Eigen::Vector3d::UnitZ());
  const VertexDynamics::State y = VertexDynamics::MakeState(q, Eigen::Vector3d::Zero());
  VertexDynamics::State dydt;
  dynamics(0.0, y, dydt);
  EXPECT_NEAR(dydt.tail<3>().norm(), 0.0, 1e-12);
  const ContactForce force = dynamics.Force(y, dydt);
  EXPECT_NEAR(force.normal_N, block.mass() * kG, 1e-12 * block.mass() * kG);
  EXPECT_NEAR(force.tangential_N, 0.0, 1e-12 * block.mass() * kG);
}

TEST(VertexDynamics, PointHeightRateIsTheDerivativeOfThePointHeight) {
  const Block block = TestBlock();
  const VertexDynamics dynamics(block, 3, kG);
  const VertexDynamics::State y0 = SpinningState();
  const double dt = 1e-5;
  for (int k : {1, 2, 4}) {
    const Eigen::Vector3d p = block.p_BV_B(k);
    const double rate = (dynamics.PointHeight(Integrate<7>(dynamics, y0, 0.05 + dt), p) -
                         dynamics.PointHeight(Integrate<7>(dynamics, y0, 0.05 - dt), p)) /
                        (2.0 * dt);
    EXPECT_NEAR(dynamics.PointHeightRate(Integrate<7>(dynamics, y0, 0.05), p), rate, 1e-8) << "V" << k;
  }
}

TEST(VertexDynamics, PivotAtAnEdgeMidpointStartedPlanarReproducesTheEdgeModel) {
  // docs/design.md §4: the 3-DOF model about the midpoint of V1V2, released from rest at tilt α with the
  // +x side lifted, must move exactly as the 1-DOF rotation about the edge.
  const Block block = TestBlock();
  const double alpha = 0.2;
  const EdgeDynamics edge(block, 1, 2, kG);
  const VertexDynamics pivot(block, edge.p_BP_B(), kG);
  const VertexDynamics::State y0 = VertexDynamics::MakeState(edge.Tilt(alpha), Eigen::Vector3d::Zero());
  for (double t_end : {0.05, 0.15, 0.25}) {
    const VertexDynamics::State y = Integrate<7>(pivot, y0, t_end);
    const EdgeDynamics::State psi = Integrate<2>(edge, EdgeDynamics::State(alpha, 0.0), t_end);
    const Eigen::Quaterniond q_edge = edge.Tilt(psi[0]);
    EXPECT_NEAR(VertexDynamics::Attitude(y).angularDistance(q_edge), 0.0, 1e-11) << "t = " << t_end;
    EXPECT_NEAR((VertexDynamics::AngularVelocity(y) - edge.AngularVelocity_B(psi)).norm(), 0.0, 1e-10)
        << "t = " << t_end;
  }
}

}  // namespace
}  // namespace rockfit::core
