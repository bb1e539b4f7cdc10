#include "rockfit/core/edge_dynamics.hpp"

#include <cmath>
#include <string>

#include "rockfit/core/errors.hpp"

namespace rockfit::core {

EdgeDynamics::EdgeDynamics(const Block& block, int i, int j, double gravity_m_s2)
    : mass_kg_(block.mass()), gravity_m_s2_(gravity_m_s2), h_m_(block.h()) {
  if (!Block::AreNeighbours(i, j)) {
    throw InvalidArgument("V" + std::to_string(Block::WrapVertex(i)) + " and V" + std::to_string(Block::WrapVertex(j)) +
                          " do not share a base edge; an edge is two neighbouring vertices such as V1V2");
  }
  p_BP_B_ = 0.5 * (block.p_BV_B(i) + block.p_BV_B(j));
  // The base centre is the origin of B, and the midpoint of a rectangle's edge lies straight out from it.
  d_m_ = p_BP_B_.norm();
  inward_B_ = -p_BP_B_ / d_m_;
  axis_B_ = inward_B_.cross(Eigen::Vector3d::UnitZ());
  p_BC_B_ = block.p_BC_B();
  inertia_C_B_ = block.inertia_C_B();
  inertia_e_ = axis_B_.dot(InertiaAboutPoint(block, p_BP_B_) * axis_B_);
  torque_scale_ = mass_kg_ * gravity_m_s2_ / inertia_e_;
  critical_angle_rad_ = std::atan2(d_m_, h_m_);
  arm_m_ = std::hypot(d_m_, h_m_);
  axis_heading_rad_ = std::atan2(axis_B_.y(), axis_B_.x());
}

Eigen::Quaterniond EdgeDynamics::Tilt(double psi_rad) const {
  return Eigen::Quaterniond(Eigen::AngleAxisd(psi_rad, axis_B_));
}

double EdgeDynamics::ComHeight(const State& y) const { return d_m_ * std::sin(y[0]) + h_m_ * std::cos(y[0]); }

double EdgeDynamics::PointHeight(const State& y, const Eigen::Vector3d& p_BX_B) const {
  // Rot(a, ψ) moves n towards e_z: the height of r = (r·n) n + (r·a) a + (r·e_z) e_z is
  // (r·n) sin ψ + (r·e_z) cos ψ.
  const Eigen::Vector3d r = p_BX_B - p_BP_B_;
  return r.dot(inward_B_) * std::sin(y[0]) + r.z() * std::cos(y[0]);
}

double EdgeDynamics::Energy(const State& y) const {
  return KineticEnergy(y) + mass_kg_ * gravity_m_s2_ * ComHeight(y);
}

ContactForce EdgeDynamics::Force(const State& y, const State& dydt, const Eigen::Quaterniond& q_yaw) const {
  const Eigen::Vector3d w_B = y[1] * axis_B_;
  const Eigen::Vector3d w_dot_B = dydt[1] * axis_B_;
  const Eigen::Quaterniond q_WB = q_yaw * Tilt(y[0]);
  const Eigen::Vector3d up_B = q_WB.conjugate() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d p_PC_B = p_BC_B_ - p_BP_B_;
  const Eigen::Vector3d a_C_B = w_dot_B.cross(p_PC_B) + w_B.cross(w_B.cross(p_PC_B));
  const Eigen::Vector3d F_B = mass_kg_ * (a_C_B + gravity_m_s2_ * up_B);
  ContactForce force;
  force.F_W = q_WB * F_B;
  force.normal_N = F_B.dot(up_B);
  force.tangential_N = (F_B - force.normal_N * up_B).norm();
  return force;
}

void EdgeDynamics::Decompose(const Eigen::Quaterniond& q_WB, Eigen::Quaterniond* q_yaw, double* psi_rad) const {
  const Eigen::Matrix3d R_WB = q_WB.normalized().toRotationMatrix();
  // Rot(a, ψ) maps n to cos ψ n + sin ψ e_z and e_z to −sin ψ n + cos ψ e_z; yaw leaves heights alone.
  const double sin_psi = R_WB.row(2).dot(inward_B_);
  const double cos_psi = R_WB(2, 2);
  *psi_rad = std::atan2(sin_psi, cos_psi);
  // The yaw: the world direction of the edge axis a_B, projected onto the ground plane.
  const Eigen::Vector3d a_W = R_WB * axis_B_;
  const double yaw_axis = std::atan2(a_W.y(), a_W.x());
  *q_yaw = Eigen::Quaterniond(Eigen::AngleAxisd(yaw_axis - axis_heading_rad_, Eigen::Vector3d::UnitZ()));
}

double EdgeDynamics::ProjectAngularVelocity(const Eigen::Vector3d& w_B, const Eigen::Vector3d& p_BQ_B) const {
  // Angular momentum about Q of the rotation about Q: J_Q w = Θ w + m c × (w × c), c = p_QC. Its component
  // along a is the same about every point of the edge line, and a·J_Q a = J_e.
  const Eigen::Vector3d c = p_BC_B_ - p_BQ_B;
  const Eigen::Vector3d L_Q_B = inertia_C_B_ * w_B + mass_kg_ * c.cross(w_B.cross(c));
  return axis_B_.dot(L_Q_B) / inertia_e_;
}

}  // namespace rockfit::core
