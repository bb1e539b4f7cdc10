// Cost of one right-hand side of vertex rocking (core/vertex_dynamics.hpp), as DOP853 calls it 12–15 times a step,
// against the same equations in the principal axes of J_P: with the state (q_WP, w_P), J_P = diag(D), Euler's
// equations read ẇ_i = τ_i/D_i + (D_j − D_k)/D_i · w_j w_k (i, j, k cyclic) and the gravity torque is c_P × up_P
// with c_P = −m g p_PC_P. Both are evaluated at the same state (the principal one rotated), and the first run
// prints how far the two ẇ differ, so that the comparison is of equal results. The principal form is not used by the
// simulator (yet): this measures what it would save (README.md, "Performance").
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "rockfit/core/vertex_dynamics.hpp"
#include "simulation_cases.hpp"

namespace {

using rockfit::core::Block;
using rockfit::core::VertexDynamics;
using State = VertexDynamics::State;

constexpr double kGravity_m_s2 = 9.81;

// A tilted attitude and a body rate of the size of Fig. 14's vertex rocking.
State SomeState() {
  const Eigen::Quaterniond q_WB(Eigen::AngleAxisd(0.2, Eigen::Vector3d(0.3, 1.0, 0.1).normalized()));
  return VertexDynamics::MakeState(q_WB, Eigen::Vector3d(0.1, -1.2, 0.3));
}

// Rotation about a fixed point in the principal axes P of J_P (R_BP = Q, a rotation).
class PrincipalVertexDynamics {
 public:
  PrincipalVertexDynamics(const VertexDynamics& dynamics, double weight_N) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(dynamics.inertia_P_B());
    R_BP_ = eigen.eigenvectors();
    if (R_BP_.determinant() < 0.0) R_BP_.col(2) *= -1.0;  // a rotation, not a reflection
    const Eigen::Vector3d D = eigen.eigenvalues();
    inverse_D_ = D.cwiseInverse();
    gyro_ = {(D.y() - D.z()) / D.x(), (D.z() - D.x()) / D.y(), (D.x() - D.y()) / D.z()};
    torque_arm_P_ = -weight_N * (R_BP_.transpose() * dynamics.p_PC_B());
  }
  const Eigen::Matrix3d& R_BP() const { return R_BP_; }

  // y = (q_WP, w_P); dydt as VertexDynamics gives it in B, here in P.
  void operator()(const State& y, State& dydt) const {
    const Eigen::Vector3d up_P = VertexDynamics::UpInBody(y);
    const Eigen::Vector3d torque_P = torque_arm_P_.cross(up_P);
    const double qw = y[0], qx = y[1], qy = y[2], qz = y[3];
    const double wx = y[4], wy = y[5], wz = y[6];
    dydt[0] = -0.5 * (qx * wx + qy * wy + qz * wz);
    dydt[1] = 0.5 * (qw * wx + qy * wz - qz * wy);
    dydt[2] = 0.5 * (qw * wy + qz * wx - qx * wz);
    dydt[3] = 0.5 * (qw * wz + qx * wy - qy * wx);
    dydt[4] = torque_P.x() * inverse_D_.x() + gyro_.x() * wy * wz;
    dydt[5] = torque_P.y() * inverse_D_.y() + gyro_.y() * wz * wx;
    dydt[6] = torque_P.z() * inverse_D_.z() + gyro_.z() * wx * wy;
  }

 private:
  Eigen::Matrix3d R_BP_;
  Eigen::Vector3d inverse_D_;
  Eigen::Vector3d gyro_;          // (D_j − D_k)/D_i
  Eigen::Vector3d torque_arm_P_;  // −m g p_PC_P
};

void BM_VertexRhsBodyFrame(benchmark::State& state) {
  const Block block = rockfit::testing::Fig14Block();
  const VertexDynamics dynamics(block, 1, kGravity_m_s2);
  State y = SomeState();
  State dydt;
  for (auto _ : state) {
    dynamics(0.0, y, dydt);
    y[4] += 1e-12 * dydt[4];  // a dependence from one call to the next, as in an integrator's stages
    benchmark::DoNotOptimize(dydt);
  }
}
BENCHMARK(BM_VertexRhsBodyFrame);

void BM_VertexRhsPrincipalAxes(benchmark::State& state) {
  const Block block = rockfit::testing::Fig14Block();
  const VertexDynamics dynamics(block, 1, kGravity_m_s2);
  const PrincipalVertexDynamics principal(dynamics, block.mass() * kGravity_m_s2);
  const State y_B = SomeState();
  const Eigen::Quaterniond q_WP =
      Eigen::Quaterniond(y_B[0], y_B[1], y_B[2], y_B[3]) * Eigen::Quaterniond(principal.R_BP());
  State y = VertexDynamics::MakeState(q_WP, principal.R_BP().transpose() * y_B.tail<3>());
  State dydt_B, dydt;
  dynamics(0.0, y_B, dydt_B);
  principal(y, dydt);
  state.counters["w_dot_difference_rel"] =
      (principal.R_BP() * dydt.tail<3>() - dydt_B.tail<3>()).norm() / dydt_B.tail<3>().norm();
  for (auto _ : state) {
    principal(y, dydt);
    y[4] += 1e-12 * dydt[4];
    benchmark::DoNotOptimize(dydt);
  }
}
BENCHMARK(BM_VertexRhsPrincipalAxes);

}  // namespace

BENCHMARK_MAIN();
