// Independent forms of the defining equations of the impact maps, written with cross products (not with
// the matrices (14) the library uses), so that tests check the maps against the paper, not against
// themselves.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "rockfit/core/general_impact_map.hpp"

namespace rockfit::testing {

// Relative residual of the angular impulse–momentum balance (13)/(17) about R, with the COM velocities
// from the kinematics (11) and (12):
//   (r_c − r_R) × m v⁺ + Θω⁺ − [(r_c − r_R) × m v⁻ + Θω⁻ + τ u_z],  v⁻ = ω⁻ × (r_c − r_b),  v⁺ = ω⁺ × (r_c − r_a),
// divided by the sum of the magnitudes of its terms.
inline double MomentumBalanceRelResidual(const core::ImpactGeometry& g, const Eigen::Vector3d& w_minus,
                                         const Eigen::Vector3d& w_plus, double tau) {
  const Eigen::Vector3d v_minus = w_minus.cross(g.p_C - g.p_b);  // (11)
  const Eigen::Vector3d v_plus = w_plus.cross(g.p_C - g.p_a);    // (12)
  const Eigen::Vector3d arm = g.p_C - g.p_R;
  const Eigen::Vector3d L_plus_orbital = arm.cross(g.mass_kg * v_plus);
  const Eigen::Vector3d L_minus_orbital = arm.cross(g.mass_kg * v_minus);
  const Eigen::Vector3d L_plus_spin = g.inertia_C * w_plus;
  const Eigen::Vector3d L_minus_spin = g.inertia_C * w_minus;
  const Eigen::Vector3d angular_impulse = tau * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d residual = L_plus_orbital + L_plus_spin - (L_minus_orbital + L_minus_spin + angular_impulse);
  const double scale = L_plus_orbital.norm() + L_plus_spin.norm() + L_minus_orbital.norm() + L_minus_spin.norm() +
                       angular_impulse.norm();
  return residual.norm() / scale;
}

// Kinetic energy ½ m |v|² + ½ ωᵀΘω of the block rotating with ω about the fixed point p_x (the COM
// velocity from the kinematics, not from the matrix form of Sect. 4.8).
inline double KineticEnergyFromComVelocity(const core::ImpactGeometry& g, const Eigen::Vector3d& p_x,
                                           const Eigen::Vector3d& w) {
  const Eigen::Vector3d v_C = w.cross(g.p_C - p_x);
  return 0.5 * g.mass_kg * v_C.squaredNorm() + 0.5 * w.dot(g.inertia_C * w);
}

// Mirror y → −y: a polar vector (x, y, z) → (x, −y, z); an axial vector (ω, τ u_z) → (−x, y, −z).
inline Eigen::Vector3d MirrorPolar(const Eigen::Vector3d& v) { return {v.x(), -v.y(), v.z()}; }
inline Eigen::Vector3d MirrorAxial(const Eigen::Vector3d& w) { return {-w.x(), w.y(), -w.z()}; }
// The base vertex that y → −y maps V_k to: V1 ↔ V2, V3 ↔ V4.
inline int MirrorVertex(int k) {
  static const int kImage[5] = {0, 2, 1, 4, 3};
  return kImage[((k - 1) % 4 + 4) % 4 + 1];
}

}  // namespace rockfit::testing
