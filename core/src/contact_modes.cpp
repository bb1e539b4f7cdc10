#include "detail/contact_modes.hpp"

#include <cmath>
#include <limits>

namespace rockfit::core::detail {
namespace {

constexpr double kPi_rad = 3.14159265358979323846;

}  // namespace

VertexMode::VertexMode(const Block& block, int vertex, double gravity_m_s2)
    : vertex_(Block::WrapVertex(vertex)), dynamics_(block, vertex_, gravity_m_s2) {
  neighbours_ = {Block::WrapVertex(vertex_ + 1), Block::WrapVertex(vertex_ - 1)};
  const Eigen::Vector3d p_KC_B = dynamics_.p_PC_B();
  for (int n = 0; n < 2; ++n) {
    p_KN_B_[n] = block.p_BV_B(neighbours_[n]) - block.p_BV_B(vertex_);
    // e_z·(u_W × c_W) = up_B·(u_B × c_B) is the signed distance (times |u|) of the COM from the vertical plane
    // through the pivot along u. σ makes it positive for the flat block, whose COM is above the base.
    const Eigen::Vector3d cross = p_KN_B_[n].cross(p_KC_B);
    edge_x_c_[n] = (cross.z() > 0.0 ? 1.0 : -1.0) * cross;
  }
}

GuardValue VertexMode::Guard(int index, const State& y) const {
  const Eigen::Vector3d up_B = VertexDynamics::UpInBody(y);
  const Eigen::Vector3d w_B = VertexDynamics::AngularVelocity(y);
  // d/dt up_B = up_B × w_B (a world-fixed vector seen from the rotating body).
  const Eigen::Vector3d up_rate_B = up_B.cross(w_B);
  if (index < 2) {
    const Eigen::Vector3d& r = p_KN_B_[index];
    return {up_B.dot(r), up_rate_B.dot(r)};
  }
  const Eigen::Vector3d& n = edge_x_c_[index - 2];
  return {up_B.dot(n), up_rate_B.dot(n)};
}

std::array<GuardValue, VertexMode::kNumGuards> VertexMode::Guards(double /*t*/, const State& y) const {
  const Eigen::Vector3d up_B = VertexDynamics::UpInBody(y);
  const Eigen::Vector3d w_B = VertexDynamics::AngularVelocity(y);
  const Eigen::Vector3d up_rate_B = up_B.cross(w_B);
  std::array<GuardValue, kNumGuards> g;
  for (int index = 0; index < 2; ++index) g[index] = {up_B.dot(p_KN_B_[index]), up_rate_B.dot(p_KN_B_[index])};
  for (int index = 2; index < 4; ++index) {
    g[index] = {up_B.dot(edge_x_c_[index - 2]), up_rate_B.dot(edge_x_c_[index - 2])};
  }
  return g;
}

double VertexMode::StepBound(const State& y) {
  const double rate_rad_s = VertexDynamics::AngularVelocity(y).norm();
  return rate_rad_s > 0.0 ? kMaxTurnPerStep_rad / rate_rad_s : std::numeric_limits<double>::infinity();
}

int VertexMode::GuardVertex(int guard) const { return neighbours_[guard == kTouchNext ? 0 : 1]; }

void VertexMode::Project(State* y) { y->head<4>().normalize(); }

Mode VertexMode::mode() const {
  Mode m;
  m.kind = ModeKind::kVertex;
  m.contact.first = vertex_;
  m.contact.second = 0;
  return m;
}

EdgeMode::EdgeMode(const Block& block, int i, int j, const Eigen::Quaterniond& q_yaw, double gravity_m_s2)
    : first_(Block::WrapVertex(i)), second_(Block::WrapVertex(j)), q_yaw_(q_yaw), dynamics_(block, i, j, gravity_m_s2) {
  SetYaw(q_yaw);
}

void EdgeMode::SetYaw(const Eigen::Quaterniond& q_yaw) {
  q_yaw_ = q_yaw;
  // The analytic Euler angles need a pure yaw and an edge axis along a body axis (the base edges of a
  // rectangular block are; the axis is built from the edge midpoint without round-off).
  const Eigen::Vector3d& a = dynamics_.axis_B();
  const bool pure_yaw = q_yaw_.x() == 0.0 && q_yaw_.y() == 0.0 && q_yaw_.w() >= 0.0;
  tilt_euler_index_ = -1;
  tilt_euler_sign_ = 1.0;
  if (pure_yaw && a.x() == 0.0 && a.z() == 0.0 && std::abs(a.y()) == 1.0) {
    tilt_euler_index_ = 1;
    tilt_euler_sign_ = a.y();
  } else if (pure_yaw && a.y() == 0.0 && a.z() == 0.0 && std::abs(a.x()) == 1.0) {
    tilt_euler_index_ = 2;
    tilt_euler_sign_ = a.x();
  }
  // q_yaw = (cos(φz/2), 0, 0, sin(φz/2)) with cos ≥ 0: φz in [−π, π].
  yaw_rad_ = 2.0 * std::atan2(q_yaw_.z(), q_yaw_.w());
}

Eigen::Vector3d EdgeMode::EulerZyx(const Eigen::Quaterniond& q_WB, const State& y) const {
  // At a yaw of ±π the general conversion's convention (φz = +π) is kept.
  if (tilt_euler_index_ < 0 || std::abs(yaw_rad_) >= kPi_rad) return EulerZyxFromUnitQuaternion(q_WB);
  Eigen::Vector3d euler(yaw_rad_, 0.0, 0.0);
  euler[tilt_euler_index_] = tilt_euler_sign_ * y[0];
  return euler;
}

GuardValue EdgeMode::Guard(int index, const State& y) const {
  if (index == kFlat) return {y[0], y[1]};
  // d/dt (d cos ψ − h sin ψ) = −(d sin ψ + h cos ψ) ψ̇.
  return {dynamics_.OverturnMargin(y), -dynamics_.ComHeight(y) * y[1]};
}

Mode EdgeMode::mode() const {
  Mode m;
  m.kind = ModeKind::kEdge;
  m.contact.first = first_;
  m.contact.second = second_;
  return m;
}

}  // namespace rockfit::core::detail
