// Rotation of the block about one of its base edges V_iV_j (1 DOF): the Edge(i,j) mode of docs/design.md §4.
//
// ψ ≥ 0 is the tilt of the base about the edge (ψ = 0: the base lies flat). With n_B the horizontal unit
// vector from the edge towards the base centre and a_B = n_B × e_z the edge axis, the attitude is
//   R_WB = R_yaw · Rot(a_B, ψ)   and   w_B = ψ̇ a_B,
// so lifting the base (ψ̇ > 0) turns n_B towards +z. For the release edge V1V2, a_B = −e_y and R_WB = Ry(−ψ):
// the +x side is lifted, and falling back (ψ̇ < 0) gives w_B = (0, +|ψ̇|, 0) as docs/design.md §2 requires.
//
// Equation of motion about the edge line: J_e ψ̈ = a·(p_PC × (−m g e_z)) with P on the edge and
// J_e = a_Bᵀ J_P a_B. With d = |horizontal distance of the COM from the edge| (b1 or b2) and h,
//   a·(p_PC × (−m g e_z)) = −m g (d cos ψ − h sin ψ) = −m g R sin(θ_c − ψ),  R = √(d² + h²), θ_c = atan(d/h).
#pragma once

#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "rockfit/core/block.hpp"
#include "rockfit/core/vertex_dynamics.hpp"

namespace rockfit::core {

class EdgeDynamics {
 public:
  static constexpr int kStateSize = 2;
  using State = Eigen::Matrix<double, kStateSize, 1>;  // (ψ [rad], ψ̇ [rad/s])

  // Throws InvalidArgument unless V_i and V_j are neighbours.
  EdgeDynamics(const Block& block, int i, int j, double gravity_m_s2);

  void operator()(double /*t*/, const State& y, State& dydt) const {
    dydt[0] = y[1];
    dydt[1] = -torque_scale_ * (d_m_ * std::cos(y[0]) - h_m_ * std::sin(y[0]));
  }

  const Eigen::Vector3d& axis_B() const { return axis_B_; }            // a_B
  const Eigen::Vector3d& inward_B() const { return inward_B_; }        // n_B
  const Eigen::Vector3d& p_BP_B() const { return p_BP_B_; }            // midpoint of the edge
  double inertia_kg_m2() const { return inertia_e_; }                  // J_e about the edge line
  double critical_angle_rad() const { return critical_angle_rad_; }  // θ_c = atan2(d, h): the COM above the edge
  double arm_m() const { return arm_m_; }                              // R = hypot(d, h)
  double offset_m() const { return d_m_; }                             // d
  double mass_kg() const { return mass_kg_; }
  double gravity_m_s2() const { return gravity_m_s2_; }
  double swing_constant_1_s2() const { return 2.0 * torque_scale_ * arm_m(); }  // K = 2 m g R / J_e

  // Rot(a_B, ψ) as a quaternion; R_WB = R_yaw · Tilt(ψ).
  Eigen::Quaterniond Tilt(double psi_rad) const;
  Eigen::Vector3d AngularVelocity_B(const State& y) const { return y[1] * axis_B_; }

  double ComHeight(const State& y) const;
  // Height of body point p_BX_B above the ground (the edge is on the ground).
  double PointHeight(const State& y, const Eigen::Vector3d& p_BX_B) const;
  double KineticEnergy(const State& y) const { return 0.5 * inertia_e_ * y[1] * y[1]; }
  double Energy(const State& y) const;
  // Signed horizontal distance of the COM from the vertical plane through the edge, positive on the base
  // side: d cos ψ − h sin ψ. It changes sign when the block overturns about the edge.
  double OverturnMargin(const State& y) const { return d_m_ * std::cos(y[0]) - h_m_ * std::sin(y[0]); }
  // Total ground force on the edge (the sum over its length), as for VertexDynamics::Force.
  ContactForce Force(const State& y, const State& dydt, const Eigen::Quaterniond& q_yaw) const;

  // Splits an attitude whose edge V_iV_j lies on the ground into yaw and tilt: R_WB = R_yaw·Tilt(ψ).
  // Any residual out-of-plane component (round-off of an event location) is dropped.
  void Decompose(const Eigen::Quaterniond& q_WB, Eigen::Quaterniond* q_yaw, double* psi_rad) const;
  // ψ̇ with the same angular momentum about the edge line as the rotation w_B about the body point
  // p_BQ_B on the edge line (e.g. one of its vertices): ψ̇ = a·(J_Q w)/(a·J_Q a) (docs/design.md §4, Zeno).
  double ProjectAngularVelocity(const Eigen::Vector3d& w_B, const Eigen::Vector3d& p_BQ_B) const;

 private:
  double mass_kg_;
  double gravity_m_s2_;
  double d_m_;
  double h_m_;
  double inertia_e_;
  double torque_scale_;  // m g / J_e
  double critical_angle_rad_;
  double arm_m_;
  double axis_heading_rad_;  // atan2 of the edge axis's y and x components in B
  Eigen::Vector3d axis_B_;
  Eigen::Vector3d inward_B_;
  Eigen::Vector3d p_BP_B_;
  Eigen::Vector3d p_BC_B_;
  Eigen::Matrix3d inertia_C_B_;
};

}  // namespace rockfit::core
