// Rotation of the block about a fixed point of its body (3 DOF): the Vertex(k) mode of docs/design.md §4, and,
// for tests and comparisons, rotation about any other body point P (e.g. the midpoint of a base edge).
//
// Newton–Euler about the fixed point P, in the body frame B:
//   J_P ẇ_B + w_B × J_P w_B = p_PC_B × R_WBᵀ(−m g e_z),   J_P = Θ + m(|c|²I − c cᵀ), c = p_PC_B,
//   q̇_WB = ½ q_WB ⊗ (0, w_B).
// P stays on the ground plane z = 0 of W; heights below are measured from it.
#pragma once

#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "rockfit/core/block.hpp"

namespace rockfit::core {

// The force the ground exerts on the block at its contact, and its split into normal and tangential parts.
struct ContactForce {
  Eigen::Vector3d F_W = Eigen::Vector3d::Zero();  // world frame [N]
  double normal_N = 0.0;                          // F·e_z (negative: the contact would have to pull)
  double tangential_N = 0.0;                      // |F − (F·e_z) e_z|
};

class VertexDynamics {
 public:
  static constexpr int kStateSize = 7;
  // (q_w, q_x, q_y, q_z, w_x, w_y, w_z): q_WB (scalar first, unit up to integration error) and w_B [rad/s].
  using State = Eigen::Matrix<double, kStateSize, 1>;

  // Rotation about base vertex V_k.
  VertexDynamics(const Block& block, int vertex, double gravity_m_s2);
  // Rotation about an arbitrary body point p_BP_B.
  VertexDynamics(const Block& block, const Eigen::Vector3d& p_BP_B, double gravity_m_s2);

  static State MakeState(const Eigen::Quaterniond& q_WB, const Eigen::Vector3d& w_B);
  // Normalised q_WB. (Eigen's normalisation divides each component by the norm; one reciprocal times each would be
  // cheaper but differs by round-off, which the chatter of response runs amplifies into different impacts.)
  static Eigen::Quaterniond Attitude(const State& y) { return Eigen::Quaterniond(y[0], y[1], y[2], y[3]).normalized(); }
  // Attitude(y) for an output sample, where the state's quaternion is of unit norm to within kNearUnitNormTol (it
  // is renormalised after every step, and the dense output between keeps it so): scaled by 1 − (|q|² − 1)/2, the
  // first-order term of 1/|q|, whose remainder (3/8)(|q|² − 1)² is below round-off there — one product where the
  // exact normalisation takes a square root and four divisions. Beyond it, Attitude(y). Samples only: the state of
  // the motion (the impacts' attitude) keeps Attitude(y), so the runs' events stay bit for bit.
  static Eigen::Quaterniond SampleAttitude(const State& y) {
    const double excess = y.head<4>().squaredNorm() - 1.0;
    if (!(std::abs(excess) <= kNearUnitNormTol)) return Attitude(y);
    const double scale = 1.0 - 0.5 * excess;
    return Eigen::Quaterniond(scale * y[0], scale * y[1], scale * y[2], scale * y[3]);
  }
  // |q|² − 1 up to which SampleAttitude's first-order scaling is exact to round-off: (3/8)·1e-16 < 2⁻⁵³.
  static constexpr double kNearUnitNormTol = 1e-8;
  static Eigen::Vector3d AngularVelocity(const State& y) { return y.tail<3>(); }
  // R_WBᵀ e_z: the world vertical in B, from a possibly non-unit quaternion (the third row of R(q) for
  // q = (w, x, y, z), scaled by 2/|q|² so that a non-unit q still gives a rotation).
  static Eigen::Vector3d UpInBody(const State& y) {
    const UpParts up = UpInBodyParts(y);
    return {up.scale * up.tilt_B.x(), up.scale * up.tilt_B.y(), 1.0 + up.scale * up.tilt_B.z()};
  }
  // R_WBᵀ e_z = scale·tilt_B + e_z: the third row of R(q) less its unit term, with the scale 2/|q|² apart, so that
  // a product with tilt_B need not wait for the division (the right-hand side scales its gravity term last).
  // UpInBody gives the same vector bit for bit.
  struct UpParts {
    double scale;            // 2/|q|²
    Eigen::Vector3d tilt_B;  // (x z − w y, y z + w x, −(x² + y²)) for q = (w, x, y, z)
  };
  static UpParts UpInBodyParts(const State& y) {
    const double qw = y[0], qx = y[1], qy = y[2], qz = y[3];
    return {2.0 / (qw * qw + qx * qx + qy * qy + qz * qz),
            Eigen::Vector3d(qx * qz - qw * qy, qy * qz + qw * qx, -(qx * qx + qy * qy))};
  }

  // The right-hand side of the equations above (time-invariant; t is ignored).
  void operator()(double /*t*/, const State& y, State& dydt) const {
    // ẇ = J_P⁻¹(−m g c × up − w × J_P w) with up = s·t + e_z (UpInBodyParts): s·(A t) + (A e_z − J_P⁻¹(w × J_P w)),
    // A = −m g J_P⁻¹[c]×, so that the division of s runs beside the products instead of before them.
    const UpParts up = UpInBodyParts(y);
    const Eigen::Vector3d w_B = y.tail<3>();
    const Eigen::Vector3d gyroscopic_B = inertia_P_B_inverse_ * w_B.cross(inertia_P_B_ * w_B);
    // Named, so that Eigen does not fold the scale into the product (which would wait for the division again).
    const Eigen::Vector3d gravity_per_scale_B = gravity_tilt_B_ * up.tilt_B;
    const Eigen::Vector3d w_dot_B = up.scale * gravity_per_scale_B + (gravity_upright_B_ - gyroscopic_B);
    const double qw = y[0], qx = y[1], qy = y[2], qz = y[3];
    dydt[0] = -0.5 * (qx * w_B.x() + qy * w_B.y() + qz * w_B.z());
    dydt[1] = 0.5 * (qw * w_B.x() + qy * w_B.z() - qz * w_B.y());
    dydt[2] = 0.5 * (qw * w_B.y() + qz * w_B.x() - qx * w_B.z());
    dydt[3] = 0.5 * (qw * w_B.z() + qx * w_B.y() - qy * w_B.x());
    dydt.tail<3>() = w_dot_B;
  }

  const Eigen::Vector3d& p_BP_B() const { return p_BP_B_; }
  const Eigen::Vector3d& p_PC_B() const { return p_PC_B_; }
  const Eigen::Matrix3d& inertia_P_B() const { return inertia_P_B_; }  // J_P

  // Height of the COM above the ground plane through P.
  double ComHeight(const State& y) const;
  // Height of body point p_BX_B above the ground plane through P, and its rate of change.
  double PointHeight(const State& y, const Eigen::Vector3d& p_BX_B) const;
  double PointHeightRate(const State& y, const Eigen::Vector3d& p_BX_B) const;
  // ½ w_Bᵀ J_P w_B + m g z_C [J].
  double KineticEnergy(const State& y) const;
  double Energy(const State& y) const;
  // Angular momentum about P in W: R_WB J_P w_B.
  Eigen::Vector3d AngularMomentum_W(const State& y) const;
  // F = m a_C + m g e_z with a_C = ẇ × c + w × (w × c); `dydt` is the right-hand side at y.
  ContactForce Force(const State& y, const State& dydt) const;
  // Force's normal_N and tangential_N alone, bit for bit (F_W left zero: no attitude to normalise and turn F by),
  // all that the segments' load diagnostics read.
  ContactForce Load(const State& y, const State& dydt) const;

 private:
  Eigen::Vector3d Force_B(const State& y, const State& dydt) const;  // F of Force, in B

  double mass_kg_;
  double weight_N_;
  Eigen::Vector3d p_BP_B_;
  Eigen::Vector3d p_PC_B_;
  Eigen::Matrix3d inertia_P_B_;
  Eigen::Matrix3d inertia_P_B_inverse_;
  Eigen::Matrix3d gravity_tilt_B_;     // A = −m g J_P⁻¹[c]× [rad/s²]: ẇ of gravity per unit of up_B
  Eigen::Vector3d gravity_upright_B_;  // A e_z [rad/s²]
};

// J_P = Θ + m(|c|²I − c cᵀ): inertia of the block about body point p_BP_B, in B (parallel-axis theorem).
Eigen::Matrix3d InertiaAboutPoint(const Block& block, const Eigen::Vector3d& p_BP_B);

}  // namespace rockfit::core
