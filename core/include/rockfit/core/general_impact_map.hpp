// The general impact map (18) of Sect. 4.3: ω⁺ = (Θ − m R_R R_a)⁻¹[(Θ − m R_R R_b) ω⁻ + τ u_z], and the
// kinetic energy about a fixed point used by (26).
#pragma once

#include <string_view>

#include <Eigen/Core>

namespace rockfit::core {

enum class ImpactStatus { kOk, kInfeasible, kAmbiguous, kSingular };
// "ok", "infeasible", "ambiguous", "singular".
const char* ToString(ImpactStatus status);
bool FromString(std::string_view text, ImpactStatus* value);  // the inverse of ToString

// The matrix to invert in (18) (or the 3×3 system of the no-spin facet map) counts as singular when its
// reciprocal condition number (1-norm estimate) is below this: fewer than ~4 significant digits of ω⁺
// would survive. Dimensionless.
inline constexpr double kImpactMinReciprocalCondition = 1e-12;

// An impact configuration, in any frame whose z axis is the world vertical. Only differences of
// positions enter (14), so the origin is arbitrary.
struct ImpactGeometry {
  double mass_kg = 0.0;
  Eigen::Matrix3d inertia_C = Eigen::Matrix3d::Zero();  // Θ about the COM, in this frame
  Eigen::Vector3d p_C = Eigen::Vector3d::Zero();        // COM
  Eigen::Vector3d p_b = Eigen::Vector3d::Zero();        // pre-impact contact point V_b
  Eigen::Vector3d p_a = Eigen::Vector3d::Zero();        // post-impact contact point V_a
  Eigen::Vector3d p_R = Eigen::Vector3d::Zero();        // where the modified wrench meets the ground plane
};

// R_x of (14): the matrix with R_x·ω = ω × (p_C − p_x), i.e. the cross-product matrix of p_x − p_C.
Eigen::Matrix3d SkewOf(const Eigen::Vector3d& p_x, const Eigen::Vector3d& p_C);

struct MapResult {
  ImpactStatus status = ImpactStatus::kOk;  // kOk or kSingular
  Eigen::Vector3d w_plus = Eigen::Vector3d::Zero();
};
// (18): ω⁺ = (Θ − m R_R R_a)⁻¹[(Θ − m R_R R_b) ω⁻ + τ u_z]. kSingular (and w_plus = 0) when the matrix
// to invert is singular to working precision (reciprocal condition below kImpactMinReciprocalCondition)
// or the result is not finite. Allocation-free.
MapResult GeneralImpactMap(const ImpactGeometry& g, const Eigen::Vector3d& w_minus, double tau);

// Kinetic energy of rotation ω about the fixed point p_x: ½ ωᵀ(Θ + m R_xᵀR_x)ω (Sect. 4.8).
double KineticEnergyAbout(const ImpactGeometry& g, const Eigen::Vector3d& p_x, const Eigen::Vector3d& w);

}  // namespace rockfit::core
