#include "detail/ground_modes.hpp"

#include <cmath>

namespace rockfit::core::detail {
namespace {

// R_WBᵀ v for the (possibly non-unit) quaternion of a Vertex-mode state.
Eigen::Vector3d BodyFromWorld(const VertexMode::State& y, const Eigen::Vector3d& v_W) {
  const Eigen::Quaterniond q(y[0], y[1], y[2], y[3]);
  return q.normalized().conjugate() * v_W;
}

}  // namespace

GroundVertexMode::GroundVertexMode(const Block& block, int vertex, double gravity_m_s2, const GroundMotion& ground,
                                   bool falls_on_side)
    : free_(block, vertex, gravity_m_s2),
      ground_(&ground),
      falls_on_side_(falls_on_side),
      mass_kg_(block.mass()),
      gravity_m_s2_(gravity_m_s2),
      p_PC_B_(free_.dynamics().p_PC_B()),
      inertia_P_B_(free_.dynamics().inertia_P_B()),
      inertia_P_B_inverse_(inertia_P_B_.inverse()) {}

void GroundVertexMode::operator()(double t, const State& y, State& dydt) const {
  const Eigen::Vector3d a_W = ground_->Acceleration_W(t);
  const Eigen::Vector3d f_W(-a_W.x(), -a_W.y(), -gravity_m_s2_ - a_W.z());
  const Eigen::Vector3d f_B = BodyFromWorld(y, f_W);
  const Eigen::Vector3d w_B = y.tail<3>();
  const Eigen::Vector3d torque_B = mass_kg_ * p_PC_B_.cross(f_B);
  const Eigen::Vector3d w_dot_B = inertia_P_B_inverse_ * (torque_B - w_B.cross(inertia_P_B_ * w_B));
  const double qw = y[0], qx = y[1], qy = y[2], qz = y[3];
  dydt[0] = -0.5 * (qx * w_B.x() + qy * w_B.y() + qz * w_B.z());
  dydt[1] = 0.5 * (qw * w_B.x() + qy * w_B.z() - qz * w_B.y());
  dydt[2] = 0.5 * (qw * w_B.y() + qz * w_B.x() - qx * w_B.z());
  dydt[3] = 0.5 * (qw * w_B.z() + qx * w_B.y() - qy * w_B.x());
  dydt.tail<3>() = w_dot_B;
}

GuardValue GroundVertexMode::SideLanding(int index, const State& y) const {
  if (index != VertexMode::kOverNext) return {1.0, 0.0};
  const Eigen::Vector3d up_B = VertexDynamics::UpInBody(y);
  // d/dt up_B = up_B × w_B (a world-fixed vector seen from the rotating body).
  return {up_B.z(), up_B.cross(VertexDynamics::AngularVelocity(y)).z()};
}

ContactForce GroundVertexMode::Force(double t, const State& y, const State& dydt) const {
  ContactForce force = Load(t, y, dydt);
  force.F_W = free_.Attitude(y) * Force_B(t, y, dydt);
  return force;
}

ContactForce GroundVertexMode::Load(double t, const State& y, const State& dydt) const {
  const Eigen::Vector3d F_B = Force_B(t, y, dydt);
  const Eigen::Vector3d up_B = VertexDynamics::UpInBody(y);
  ContactForce force;
  force.normal_N = F_B.dot(up_B);
  force.tangential_N = (F_B - force.normal_N * up_B).norm();
  return force;
}

Eigen::Vector3d GroundVertexMode::Force_B(double t, const State& y, const State& dydt) const {
  const Eigen::Vector3d a_W = ground_->Acceleration_W(t);
  const Eigen::Vector3d f_W(-a_W.x(), -a_W.y(), -gravity_m_s2_ - a_W.z());
  const Eigen::Vector3d f_B = BodyFromWorld(y, f_W);
  const Eigen::Vector3d w_B = y.tail<3>();
  const Eigen::Vector3d w_dot_B = dydt.tail<3>();
  const Eigen::Vector3d a_C_B = w_dot_B.cross(p_PC_B_) + w_B.cross(w_B.cross(p_PC_B_));
  return mass_kg_ * (a_C_B - f_B);
}

GroundEdgeMode::GroundEdgeMode(const Block& block, int i, int j, const Eigen::Quaterniond& q_yaw, double gravity_m_s2,
                               const GroundMotion& ground, bool falls_on_side, double lift_margin_g)
    : free_(block, i, j, q_yaw, gravity_m_s2),
      ground_(&ground),
      lift_margin_g_(lift_margin_g),
      falls_on_side_(falls_on_side),
      mass_kg_(block.mass()),
      gravity_m_s2_(gravity_m_s2),
      d_m_(free_.dynamics().offset_m()),
      h_m_(block.h()),
      torque_scale_(block.mass() / free_.dynamics().inertia_kg_m2()),
      about_first_(block, i, gravity_m_s2, ground),
      about_second_(block, j, gravity_m_s2, ground) {
  const EdgeDynamics& e = free_.dynamics();
  inward_W_ = q_yaw * e.inward_B();
  p_PC_B_ = block.p_BC_B() - e.p_BP_B();
  const Eigen::Vector3d along_B = block.p_BV_B(free_.second()) - block.p_BV_B(free_.first());
  half_length_m_ = 0.5 * along_B.norm();
  edge_dir_B_ = along_B.normalized();
  first_to_second_B_ = along_B;
  inertia_P_B_ = InertiaAboutPoint(block, e.p_BP_B());
}

void GroundEdgeMode::SetYawAndLiftMargin(const Eigen::Quaterniond& q_yaw, double lift_margin_g) {
  free_.SetYaw(q_yaw);
  inward_W_ = q_yaw * free_.dynamics().inward_B();
  lift_margin_g_ = lift_margin_g;
}

void GroundEdgeMode::operator()(double t, const State& y, State& dydt) const {
  const Eigen::Vector3d a_W = ground_->Acceleration_W(t);
  const double f_n = -a_W.dot(inward_W_);
  const double f_z = -gravity_m_s2_ - a_W.z();
  const double c = std::cos(y[0]);
  const double s = std::sin(y[0]);
  dydt[0] = y[1];
  dydt[1] = torque_scale_ * (f_z * (d_m_ * c - h_m_ * s) - f_n * (d_m_ * s + h_m_ * c));
}

Eigen::Vector3d GroundEdgeMode::Field_B(double t, double psi) const {
  const Eigen::Vector3d a_W = ground_->Acceleration_W(t);
  const Eigen::Vector3d f_W(-a_W.x(), -a_W.y(), -gravity_m_s2_ - a_W.z());
  const Eigen::Quaterniond q_WB = free_.q_yaw() * free_.dynamics().Tilt(psi);
  return q_WB.conjugate() * f_W;
}

ContactForce GroundEdgeMode::Force(double t, const State& y, const State& dydt) const {
  const Eigen::Vector3d& axis_B = free_.dynamics().axis_B();
  const Eigen::Vector3d w_B = y[1] * axis_B;
  const Eigen::Vector3d w_dot_B = dydt[1] * axis_B;
  const Eigen::Quaterniond q_WB = free_.Attitude(y);
  const Eigen::Vector3d up_B = q_WB.conjugate() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d a_C_B = w_dot_B.cross(p_PC_B_) + w_B.cross(w_B.cross(p_PC_B_));
  const Eigen::Vector3d F_B = mass_kg_ * (a_C_B - Field_B(t, y[0]));
  ContactForce force;
  force.F_W = q_WB * F_B;
  force.normal_N = F_B.dot(up_B);
  force.tangential_N = (F_B - force.normal_N * up_B).norm();
  return force;
}

std::array<double, 2> GroundEdgeMode::EndForces(double t, const State& y) const {
  State dydt;
  (*this)(t, y, dydt);
  const Eigen::Vector3d& axis_B = free_.dynamics().axis_B();
  const Eigen::Vector3d w_B = y[1] * axis_B;
  const Eigen::Vector3d w_dot_B = dydt[1] * axis_B;
  const Eigen::Vector3d f_B = Field_B(t, y[0]);
  const Eigen::Vector3d up_B = free_.Attitude(y).conjugate() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d a_C_B = w_dot_B.cross(p_PC_B_) + w_B.cross(w_B.cross(p_PC_B_));
  const Eigen::Vector3d F_B = mass_kg_ * (a_C_B - f_B);
  // The contact moment about the edge midpoint P that the motion needs: dL_P/dt minus the moment of the
  // field at the COM. Its component along ê × up is (L/2)(N_j − N_i) (ê horizontal, from V_i to V_j).
  const Eigen::Vector3d moment_B =
      inertia_P_B_ * w_dot_B + w_B.cross(inertia_P_B_ * w_B) - mass_kg_ * p_PC_B_.cross(f_B);
  const double normal = F_B.dot(up_B);
  const double difference = moment_B.dot(edge_dir_B_.cross(up_B)) / half_length_m_;
  return {0.5 * (normal - difference), 0.5 * (normal + difference)};
}

double GroundEdgeMode::LiftAcceleration(int end, double t, const State& y) const {
  const GroundVertexMode& about = end == 0 ? about_second_ : about_first_;
  const Eigen::Vector3d r_B = end == 0 ? Eigen::Vector3d(-first_to_second_B_) : first_to_second_B_;
  const GroundVertexMode::State yv = VertexDynamics::MakeState(free_.Attitude(y), free_.AngularVelocity_B(y));
  GroundVertexMode::State dydt;
  about(t, yv, dydt);
  const Eigen::Vector3d w_B = yv.tail<3>();
  const Eigen::Vector3d up_B = VertexDynamics::UpInBody(yv);
  return up_B.dot(dydt.tail<3>().cross(r_B) + w_B.cross(w_B.cross(r_B)));
}

double GroundEdgeMode::EndHold(int end, double t, const State& y) const {
  return EndHoldWith(end, t, y, EndForces(t, y));
}

double GroundEdgeMode::EndHoldWith(int end, double t, const State& y, const std::array<double, 2>& end_forces_N) const {
  const double g = gravity_m_s2_;
  return std::max(-LiftAcceleration(end, t, y) / g, end_forces_N[static_cast<std::size_t>(end)] / (mass_kg_ * g)) +
         lift_margin_g_;
}

std::array<double, 2> GroundEdgeMode::EndHolds(double t, const State& y) const {
  const std::array<double, 2> forces = EndForces(t, y);
  return {EndHoldWith(0, t, y, forces), EndHoldWith(1, t, y, forces)};
}

GuardValue GroundEdgeMode::Guard(int index, double t, const State& y) const {
  // Under OverturnRule::kFallsOnSide the block lies on a side at ψ = π/2: the guard is cos ψ.
  if (index == kOver && falls_on_side_) return {std::cos(y[0]), -std::sin(y[0]) * y[1]};
  if (index < EdgeMode::kNumGuards) return free_.Guard(index, y);
  const int end = index - kLoadFirst;
  // The rate by a central difference along the motion (y ± δ·ẏ at t ± δ): it decides whether a load that starts
  // at zero rises or falls and whether a step holds an interior minimum, and it is the slope of the Newton steps
  // that polish a crossing (its O(δ²) error only slows their convergence).
  State dydt;
  (*this)(t, y, dydt);
  const double ahead = EndHold(end, t + kLoadRateStep_s, y + kLoadRateStep_s * dydt);
  const double behind = EndHold(end, t - kLoadRateStep_s, y - kLoadRateStep_s * dydt);
  return {EndHold(end, t, y), (ahead - behind) / (2.0 * kLoadRateStep_s)};
}

std::array<GuardValue, GroundEdgeMode::kNumGuards> GroundEdgeMode::Guards(double t, const State& y) const {
  std::array<GuardValue, kNumGuards> g;
  g[kFlat] = Guard(kFlat, t, y);
  g[kOver] = Guard(kOver, t, y);
  // The end loads and their central differences as in Guard.
  State dydt;
  (*this)(t, y, dydt);
  const std::array<double, 2> ahead = EndHolds(t + kLoadRateStep_s, y + kLoadRateStep_s * dydt);
  const std::array<double, 2> behind = EndHolds(t - kLoadRateStep_s, y - kLoadRateStep_s * dydt);
  const std::array<double, 2> now = EndHolds(t, y);
  for (int end = 0; end < 2; ++end) {
    const auto k = static_cast<std::size_t>(end);
    g[kLoadFirst + end] = {now[k], (ahead[k] - behind[k]) / (2.0 * kLoadRateStep_s)};
  }
  return g;
}

}  // namespace rockfit::core::detail
