// The contact modes and rigid-body dynamics of one block, built once per run and reused by every segment and
// impact. Building them (the inertia about a point and its inverse, the edge geometry) cost as much as the rest of
// a planar impact; a run visits at most four vertices and four edges. Internal to the simulator.
#pragma once

#include <array>

#include <Eigen/Geometry>

#include "detail/contact_modes.hpp"
#include "detail/ground_modes.hpp"
#include "detail/lazy_slot.hpp"
#include "rockfit/core/block.hpp"
#include "rockfit/core/contact.hpp"
#include "rockfit/core/edge_dynamics.hpp"
#include "rockfit/core/vertex_dynamics.hpp"

namespace rockfit::core::detail {

class ModeCache {
 public:
  // `ground` null: free rocking (the ground modes are not available). falls_on_side: OverturnRule::kFallsOnSide.
  ModeCache(const Block& block, double gravity_m_s2, const GroundMotion* ground, bool falls_on_side)
      : block_(block), gravity_m_s2_(gravity_m_s2), ground_(ground), falls_on_side_(falls_on_side) {}
  ModeCache(const ModeCache&) = delete;
  ModeCache& operator=(const ModeCache&) = delete;

  // The dynamics about the edge V_iV_j (either order: they do not depend on it).
  const EdgeDynamics& EdgeDynamicsOf(int i, int j) {
    LazySlot<EdgeDynamics>& slot = edge_dynamics_[EdgeSlot(i, j) / 2];
    if (!slot) slot.emplace(block_, i, j, gravity_m_s2_);
    return *slot;
  }
  const VertexMode& Vertex(int k) {
    LazySlot<VertexMode>& slot = vertex_modes_[Block::WrapVertex(k) - 1];
    if (!slot) slot.emplace(block_, k, gravity_m_s2_);
    return *slot;
  }
  const VertexDynamics& VertexDynamicsOf(int k) { return Vertex(k).dynamics(); }
  // The Edge mode V_iV_j (in this order) with yaw q_yaw. The reference stays valid, with this yaw, until the next
  // call for the same edge.
  const EdgeMode& Edge(int i, int j, const Eigen::Quaterniond& q_yaw) {
    LazySlot<EdgeMode>& slot = edge_modes_[EdgeSlot(i, j)];
    if (slot) {
      slot->SetYaw(q_yaw);
    } else {
      slot.emplace(block_, i, j, q_yaw, gravity_m_s2_);
    }
    return *slot;
  }
  const GroundVertexMode& GroundVertex(int k) {
    LazySlot<GroundVertexMode>& slot = ground_vertex_modes_[Block::WrapVertex(k) - 1];
    if (!slot) slot.emplace(block_, k, gravity_m_s2_, *ground_, falls_on_side_);
    return *slot;
  }
  // As Edge, under ground motion, with the lift margin of GroundEdgeMode.
  const GroundEdgeMode& GroundEdge(int i, int j, const Eigen::Quaterniond& q_yaw, double lift_margin_g) {
    LazySlot<GroundEdgeMode>& slot = ground_edge_modes_[EdgeSlot(i, j)];
    if (slot) {
      slot->SetYawAndLiftMargin(q_yaw, lift_margin_g);
    } else {
      slot.emplace(block_, i, j, q_yaw, gravity_m_s2_, *ground_, falls_on_side_, lift_margin_g);
    }
    return *slot;
  }

 private:
  // 2·(first vertex of the edge in cyclic order − 1), plus 1 when V_i is the second: eight ordered edges.
  // Throws (through Contact::Edge) unless V_i and V_j are neighbours.
  static int EdgeSlot(int i, int j) {
    const Contact edge = Contact::Edge(i, j);
    return 2 * (edge.first - 1) + (Block::WrapVertex(i) == edge.first ? 0 : 1);
  }

  const Block& block_;
  double gravity_m_s2_;
  const GroundMotion* ground_;
  bool falls_on_side_;
  std::array<LazySlot<EdgeDynamics>, 4> edge_dynamics_;
  std::array<LazySlot<VertexMode>, 4> vertex_modes_;
  std::array<LazySlot<EdgeMode>, 8> edge_modes_;
  std::array<LazySlot<GroundVertexMode>, 4> ground_vertex_modes_;
  std::array<LazySlot<GroundEdgeMode>, 8> ground_edge_modes_;
};

}  // namespace rockfit::core::detail
