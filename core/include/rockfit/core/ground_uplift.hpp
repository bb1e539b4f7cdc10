// Rest to rocking under ground motion: when a flat block at rest on the table starts to rock.
//
// In the ground frame the block carries its weight −m g e_z and the inertial force −m a_g at the COM. About a
// base edge with inward horizontal unit normal n (from the edge towards the base centre) at distance d from
// the centre, the moment that lifts the base is
//   M_e(t) = m [h (a_g(t)·n) − d (g + a_g,z(t))],
// and the block stays at rest while M_e ≤ 0 for all four edges (planar: |a_g| ≤ g·b/h). a_g is linear between
// record samples, so each M_e is linear there and its sign change is found exactly. When the margins of both
// edges at a vertex are positive at that instant, the block starts rocking about the vertex (the contact-force
// sign test of Vertex mode); otherwise about the edge, and the Edge mode's end-force guards take it on to a
// vertex when the lateral part of the inertial force unloads one end of the edge.
#pragma once

#include <array>
#include <optional>

#include <Eigen/Geometry>

#include "rockfit/core/block.hpp"
#include "rockfit/core/contact.hpp"
#include "rockfit/core/ground_motion.hpp"

namespace rockfit::core {

struct Uplift {
  double t_s = 0.0;
  Contact contact;  // the edge or vertex the block starts to rock about
};

// M_e/m [m²/s²] of the four base edges V1V2, V2V3, V3V4, V4V1 (in this order) for the flat block with yaw
// q_yaw under ground acceleration a_W.
std::array<double, 4> UpliftMargins(const Block& block, const Eigen::Quaterniond& q_yaw, double gravity_m_s2,
                                    const Eigen::Vector3d& a_W);

// The first time in [t_from, t_until] at which a margin becomes positive (t_from itself when one already
// is), with the contact; empty if the block stays at rest.
std::optional<Uplift> NextUplift(const Block& block, const GroundMotion& ground, const Eigen::Quaterniond& q_yaw,
                                 double gravity_m_s2, double t_from_s, double t_until_s);

}  // namespace rockfit::core
