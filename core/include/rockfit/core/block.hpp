// The rigid block: a homogeneous cuboid 2b1 × 2b2 × 2h (docs/design.md §2).
//
// Body frame B: origin at the centre of the base facet, x along b1, y along b2, z up; the COM is at
// (0, 0, h). Base vertices are numbered cyclically 1..4:
//   V1 = (−b1, −b2, 0), V2 = (−b1, +b2, 0), V3 = (+b1, +b2, 0), V4 = (+b1, −b2, 0).
// A Block is immutable once made; every impact map and the simulator take it by const reference.
#pragma once

#include <Eigen/Core>

namespace rockfit::core {

// Standard gravity used unless a caller configures another value [m/s²].
inline constexpr double kStandardGravity = 9.81;

class Block {
 public:
  // Half-sizes b1, b2, h [m] and density [kg/m³]. Throws InvalidArgument for non-positive or
  // non-finite values, with a message naming the offending quantity.
  static Block FromDensity(double b1_m, double b2_m, double h_m, double density_kg_m3);
  // Half-sizes [m] and total mass [kg].
  static Block FromMass(double b1_m, double b2_m, double h_m, double mass_kg);

  double b1() const { return b1_; }
  double b2() const { return b2_; }
  double h() const { return h_; }
  double mass() const { return mass_; }
  double density() const { return mass_ / (8.0 * b1_ * b2_ * h_); }

  // Θ about the COM in B: m/3·diag(b2²+h², b1²+h², b1²+b2²).
  const Eigen::Matrix3d& inertia_C_B() const { return inertia_C_B_; }
  // Position of the COM in B: (0, 0, h).
  Eigen::Vector3d p_BC_B() const { return {0.0, 0.0, h_}; }
  // Position of base vertex V_k in B, k ∈ {1, 2, 3, 4}; other k are taken cyclically (k = 0 is V4,
  // k = 5 is V1), as the paper's indices b−1, b+1 are.
  Eigen::Vector3d p_BV_B(int k) const;
  // Wraps any integer vertex index into 1..4.
  static int WrapVertex(int k) { return ((k - 1) % 4 + 4) % 4 + 1; }
  // True when vertices i and j share a base edge (they are cyclic neighbours).
  static bool AreNeighbours(int i, int j);

 private:
  Block(double b1, double b2, double h, double mass);

  double b1_;
  double b2_;
  double h_;
  double mass_;
  Eigen::Matrix3d inertia_C_B_;
};

}  // namespace rockfit::core
