#include "rockfit/core/vertex_dynamics.hpp"

namespace rockfit::core {

Eigen::Matrix3d InertiaAboutPoint(const Block& block, const Eigen::Vector3d& p_BP_B) {
  const Eigen::Vector3d c = block.p_BC_B() - p_BP_B;
  return block.inertia_C_B() + block.mass() * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
}

VertexDynamics::VertexDynamics(const Block& block, int vertex, double gravity_m_s2)
    : VertexDynamics(block, block.p_BV_B(vertex), gravity_m_s2) {}

VertexDynamics::VertexDynamics(const Block& block, const Eigen::Vector3d& p_BP_B, double gravity_m_s2)
    : mass_kg_(block.mass()),
      weight_N_(block.mass() * gravity_m_s2),
      p_BP_B_(p_BP_B),
      p_PC_B_(block.p_BC_B() - p_BP_B),
      inertia_P_B_(InertiaAboutPoint(block, p_BP_B)),
      inertia_P_B_inverse_(inertia_P_B_.inverse()) {
  Eigen::Matrix3d cross_c;  // [c]×: cross_c v = c × v
  cross_c << 0.0, -p_PC_B_.z(), p_PC_B_.y(), p_PC_B_.z(), 0.0, -p_PC_B_.x(), -p_PC_B_.y(), p_PC_B_.x(), 0.0;
  gravity_tilt_B_ = -weight_N_ * (inertia_P_B_inverse_ * cross_c);
  gravity_upright_B_ = gravity_tilt_B_.col(2);
}

VertexDynamics::State VertexDynamics::MakeState(const Eigen::Quaterniond& q_WB, const Eigen::Vector3d& w_B) {
  State y;
  y << q_WB.w(), q_WB.x(), q_WB.y(), q_WB.z(), w_B;
  return y;
}

double VertexDynamics::ComHeight(const State& y) const { return UpInBody(y).dot(p_PC_B_); }

double VertexDynamics::PointHeight(const State& y, const Eigen::Vector3d& p_BX_B) const {
  return UpInBody(y).dot(p_BX_B - p_BP_B_);
}

double VertexDynamics::PointHeightRate(const State& y, const Eigen::Vector3d& p_BX_B) const {
  // d/dt e_z·R r = (R_WBᵀe_z)·(w_B × r).
  return UpInBody(y).dot(AngularVelocity(y).cross(p_BX_B - p_BP_B_));
}

double VertexDynamics::KineticEnergy(const State& y) const {
  const Eigen::Vector3d w_B = AngularVelocity(y);
  return 0.5 * w_B.dot(inertia_P_B_ * w_B);
}

double VertexDynamics::Energy(const State& y) const { return KineticEnergy(y) + weight_N_ * ComHeight(y); }

Eigen::Vector3d VertexDynamics::AngularMomentum_W(const State& y) const {
  return Attitude(y).toRotationMatrix() * (inertia_P_B_ * AngularVelocity(y));
}

Eigen::Vector3d VertexDynamics::Force_B(const State& y, const State& dydt) const {
  const Eigen::Vector3d w_B = AngularVelocity(y);
  const Eigen::Vector3d w_dot_B = dydt.tail<3>();
  // Acceleration of the COM (P fixed), expressed in B.
  const Eigen::Vector3d a_C_B = w_dot_B.cross(p_PC_B_) + w_B.cross(w_B.cross(p_PC_B_));
  return mass_kg_ * a_C_B + weight_N_ * UpInBody(y);
}

ContactForce VertexDynamics::Load(const State& y, const State& dydt) const {
  const Eigen::Vector3d F_B = Force_B(y, dydt);
  const Eigen::Vector3d up_B = UpInBody(y);
  ContactForce force;
  force.normal_N = F_B.dot(up_B);
  force.tangential_N = (F_B - force.normal_N * up_B).norm();
  return force;
}

ContactForce VertexDynamics::Force(const State& y, const State& dydt) const {
  ContactForce force = Load(y, dydt);
  force.F_W = Attitude(y).toRotationMatrix() * Force_B(y, dydt);
  return force;
}

}  // namespace rockfit::core
