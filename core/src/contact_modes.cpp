#include "detail/contact_modes.hpp"

#include <cmath>
#include <limits>

namespace rockfit::core::detail {

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
    : first_(Block::WrapVertex(i)), second_(Block::WrapVertex(j)), q_yaw_(q_yaw), dynamics_(block, i, j, gravity_m_s2) {}

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
