#include "rockfit/core/edge_impact.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include <Eigen/Geometry>
#include <gsl/gsl_poly.h>

#include "detail/conditioned_solve.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/core/gsl_setup.hpp"

namespace rockfit::core {
namespace {

// R_WB passed to EdgeImpact must satisfy |R_WBᵀR_WB − I| ≤ this (max entry) and det R_WB > 0. Generous:
// it rejects matrices that are not rotations, not the round-off of a normalised quaternion. Dimensionless.
constexpr double kRotationTol = 1e-6;
// A coefficient of the determinant polynomial smaller than this times the largest one is round-off (the
// cubic coefficient is zero analytically); keeping it would create a spurious root near ±1/tol. Dimensionless.
constexpr double kPolynomialCoefficientRelTol = 1e-12;

void RequireNeighbours(int pivot, int landing) {
  if (!Block::AreNeighbours(pivot, landing)) {
    throw InvalidArgument("an edge impact needs the landing vertex V" + std::to_string(Block::WrapVertex(landing)) +
                          " to be a neighbour of the pivot V" + std::to_string(Block::WrapVertex(pivot)) +
                          " (base edges: V1V2, V2V3, V3V4, V4V1)");
  }
}

void RequireRotation(const Eigen::Matrix3d& R_WB) {
  if (!R_WB.allFinite() || (R_WB.transpose() * R_WB - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > kRotationTol ||
      R_WB.determinant() <= 0.0) {
    throw InvalidArgument("edge impact: R_WB must be a rotation matrix (orthonormal, determinant +1)");
  }
}

// The impact configuration in W. The origin of W is irrelevant (only differences enter (14)); the body
// origin is used.
ImpactGeometry EdgeGeometry(const Block& block, const Eigen::Matrix3d& R_WB, int pivot, int landing, double lambda) {
  ImpactGeometry g;
  g.mass_kg = block.mass();
  g.inertia_C = R_WB * block.inertia_C_B() * R_WB.transpose();  // Θ_W = R_WB Θ R_WBᵀ
  g.p_C = R_WB * block.p_BC_B();
  g.p_b = R_WB * block.p_BV_B(pivot);
  g.p_a = R_WB * block.p_BV_B(landing);
  g.p_R = 0.5 * (g.p_a + g.p_b) + 0.5 * lambda * (g.p_a - g.p_b);  // (19)
  return g;
}

// det[c0 c1 c2] of three columns (scalar triple product).
double Det3(const Eigen::Vector3d& c0, const Eigen::Vector3d& c1, const Eigen::Vector3d& c2) {
  return c0.dot(c1.cross(c2));
}

}  // namespace

void EdgeImpactParameters::Validate() const {
  if (!std::isfinite(lambda)) throw InvalidArgument("edge impact: λ must be finite, got " + std::to_string(lambda));
  if (!std::isfinite(tau)) throw InvalidArgument("edge impact: τ must be finite [N·m·s], got " + std::to_string(tau));
}

bool WithinEdgeBounds(double lambda) { return lambda >= -1.0 && lambda <= 1.0; }  // (25)

Eigen::Matrix3d EdgeImpactAttitude(const Block& block, int pivot, int landing, double tilt_rad) {
  RequireNeighbours(pivot, landing);
  if (!std::isfinite(tilt_rad) || tilt_rad < 0.0 || tilt_rad > kMaxEdgeImpactTilt) {
    throw InvalidArgument("edge impact: the tilt must be in [0, π/2] rad, got " + std::to_string(tilt_rad));
  }
  // Horizontal unit vector from the edge towards the base centre (perpendicular to the edge for a
  // rectangular base). Rotating about k = n_in × e_z by +tilt moves that side up: (k × n_in) = e_z.
  const Eigen::Vector3d mid_B = 0.5 * (block.p_BV_B(pivot) + block.p_BV_B(landing));
  const Eigen::Vector3d n_in_B = Eigen::Vector3d(-mid_B.x(), -mid_B.y(), 0.0).normalized();
  const Eigen::Vector3d axis_B = n_in_B.cross(Eigen::Vector3d::UnitZ());
  return Eigen::AngleAxisd(tilt_rad, axis_B).toRotationMatrix();
}

ImpactOutcome EdgeImpact(const Block& block, const Eigen::Matrix3d& R_WB, int pivot, int landing,
                         const Eigen::Vector3d& w_minus_W, const EdgeImpactParameters& params) {
  RequireNeighbours(pivot, landing);
  RequireRotation(R_WB);
  params.Validate();
  if (!w_minus_W.allFinite()) throw InvalidArgument("edge impact: ω⁻ must be finite");

  const ImpactGeometry g = EdgeGeometry(block, R_WB, pivot, landing, params.lambda);
  ImpactOutcome out;
  out.w_minus_W = w_minus_W;
  out.contact_before = Contact::Vertex(pivot);
  out.energy_before_J = KineticEnergyAbout(g, g.p_b, w_minus_W);
  out.within_geometric_bounds = WithinEdgeBounds(params.lambda);
  out.tau = params.tau;

  const MapResult map = GeneralImpactMap(g, w_minus_W, params.tau);  // (20) = (18) with (19)
  if (map.status != ImpactStatus::kOk) {
    out.status = map.status;
    return out;
  }
  out.w_plus_W = map.w_plus;
  out.w_plus_B = R_WB.transpose() * map.w_plus;

  // Contact after: V_b lifts off if its vertical velocity while rotating about V_a is positive.
  const Eigen::Vector3d p_ab = g.p_b - g.p_a;
  const double v_b_up = map.w_plus.cross(p_ab).z();
  const double v_tol = kContactVelocityRelTol * map.w_plus.norm() * p_ab.norm();
  out.contact_after = v_b_up > v_tol ? Contact::Vertex(landing) : Contact::Edge(pivot, landing);

  out.energy_after_J = KineticEnergyAbout(g, g.p_a, map.w_plus);
  out.delta_energy_J = out.energy_after_J - out.energy_before_J;  // (26)
  out.energy_nonincreasing = out.delta_energy_J <= kEnergyRelTol * out.energy_before_J;
  return out;
}

EdgeImpactOperators MakeEdgeImpactOperators(const Block& block, int pivot, int landing,
                                            const EdgeImpactParameters& params) {
  RequireNeighbours(pivot, landing);
  params.Validate();
  EdgeImpactOperators operators;
  operators.pivot = Block::WrapVertex(pivot);
  operators.landing = Block::WrapVertex(landing);
  operators.params = params;
  // The geometry of (19) in B: R_WB = I.
  const ImpactGeometry g = EdgeGeometry(block, Eigen::Matrix3d::Identity(), pivot, landing, params.lambda);
  const Eigen::Matrix3d R_R = SkewOf(g.p_R, g.p_C);
  const Eigen::Matrix3d R_a = SkewOf(g.p_a, g.p_C);
  const Eigen::Matrix3d R_b = SkewOf(g.p_b, g.p_C);
  const Eigen::Matrix3d A = g.inertia_C - g.mass_kg * R_R * R_a;  // (18): Θ − m R_R R_a
  const Eigen::Matrix3d N = g.inertia_C - g.mass_kg * R_R * R_b;  //       Θ − m R_R R_b
  // A⁻¹ with the conditioned solve's test of (18).
  Eigen::Matrix3d A_inv;
  operators.solvable = detail::InvertConditioned3(A, kImpactMinReciprocalCondition, &A_inv) && A_inv.allFinite();
  if (operators.solvable) {
    operators.w_plus_from_w_minus_B = A_inv * N;
    operators.w_plus_from_up_B = A_inv;
  }
  operators.inertia_b_B = g.inertia_C + g.mass_kg * R_b.transpose() * R_b;
  operators.inertia_a_B = g.inertia_C + g.mass_kg * R_a.transpose() * R_a;
  operators.p_ab_B = g.p_b - g.p_a;
  return operators;
}

ImpactOutcome EdgeImpact(const EdgeImpactOperators& operators, const Eigen::Matrix3d& R_WB,
                         const Eigen::Vector3d& w_minus_B) {
  if (!w_minus_B.allFinite()) throw InvalidArgument("edge impact: ω⁻ must be finite");
  ImpactOutcome out;
  out.w_minus_W = R_WB * w_minus_B;
  out.contact_before = Contact::Vertex(operators.pivot);
  out.energy_before_J = 0.5 * w_minus_B.dot(operators.inertia_b_B * w_minus_B);
  out.within_geometric_bounds = WithinEdgeBounds(operators.params.lambda);
  out.tau = operators.params.tau;
  if (!operators.solvable) {
    out.status = ImpactStatus::kSingular;
    return out;
  }
  const Eigen::Vector3d up_B = R_WB.row(2).transpose();  // R_WBᵀ u_z
  const Eigen::Vector3d w_plus_B =
      operators.w_plus_from_w_minus_B * w_minus_B + operators.params.tau * (operators.w_plus_from_up_B * up_B);  // (18)
  if (!w_plus_B.allFinite()) {
    out.status = ImpactStatus::kSingular;
    return out;
  }
  out.w_plus_B = w_plus_B;
  out.w_plus_W = R_WB * w_plus_B;
  // Contact after, as EdgeImpact in W: u_z·(ω⁺ × p_ab) = up_B·(ω⁺_B × p_ab_B).
  const double v_b_up = up_B.dot(w_plus_B.cross(operators.p_ab_B));
  const double v_tol = kContactVelocityRelTol * w_plus_B.norm() * operators.p_ab_B.norm();
  out.contact_after =
      v_b_up > v_tol ? Contact::Vertex(operators.landing) : Contact::Edge(operators.pivot, operators.landing);
  out.energy_after_J = 0.5 * w_plus_B.dot(operators.inertia_a_B * w_plus_B);
  out.delta_energy_J = out.energy_after_J - out.energy_before_J;  // (26)
  out.energy_nonincreasing = out.delta_energy_J <= kEnergyRelTol * out.energy_before_J;
  return out;
}

std::vector<double> EdgeImpactSingularLambdas(const Block& block, const Eigen::Matrix3d& R_WB, int pivot,
                                              int landing) {
  RequireNeighbours(pivot, landing);
  RequireRotation(R_WB);
  // Θ − m R_R(λ) R_a = A + λ B with R_R(λ) = (R_a + R_b)/2 + λ(R_a − R_b)/2 (19):
  //   A = Θ − m (R_a + R_b)/2 R_a,  B = −m (R_a − R_b)/2 R_a.
  // det(A + λB) is multilinear in the columns: the coefficient of λᵏ sums the determinants with k columns
  // taken from B and 3 − k from A.
  const ImpactGeometry g = EdgeGeometry(block, R_WB, pivot, landing, 0.0);
  const Eigen::Matrix3d R_a = SkewOf(g.p_a, g.p_C);
  const Eigen::Matrix3d R_b = SkewOf(g.p_b, g.p_C);
  const Eigen::Matrix3d A = g.inertia_C - g.mass_kg * 0.5 * (R_a + R_b) * R_a;
  const Eigen::Matrix3d B = -g.mass_kg * 0.5 * (R_a - R_b) * R_a;
  std::array<double, 4> c{};  // c[k]: coefficient of λᵏ
  c[0] = Det3(A.col(0), A.col(1), A.col(2));
  c[1] = Det3(B.col(0), A.col(1), A.col(2)) + Det3(A.col(0), B.col(1), A.col(2)) + Det3(A.col(0), A.col(1), B.col(2));
  c[2] = Det3(A.col(0), B.col(1), B.col(2)) + Det3(B.col(0), A.col(1), B.col(2)) + Det3(B.col(0), B.col(1), A.col(2));
  c[3] = Det3(B.col(0), B.col(1), B.col(2));

  const double largest = std::max({std::abs(c[0]), std::abs(c[1]), std::abs(c[2]), std::abs(c[3])});
  int degree = 3;
  while (degree > 0 && std::abs(c[degree]) <= kPolynomialCoefficientRelTol * largest) --degree;

  std::vector<double> roots;
  double x[3] = {0.0, 0.0, 0.0};
  int n = 0;
  EnsureGslErrorHandlerOff();  // every GSL user turns the aborting handler off through the one helper
  if (degree == 3) {
    n = gsl_poly_solve_cubic(c[2] / c[3], c[1] / c[3], c[0] / c[3], &x[0], &x[1], &x[2]);
  } else if (degree == 2) {
    n = gsl_poly_solve_quadratic(c[2], c[1], c[0], &x[0], &x[1]);
  } else if (degree == 1) {
    x[0] = -c[0] / c[1];
    n = 1;
  }
  roots.assign(x, x + n);
  std::sort(roots.begin(), roots.end());
  return roots;
}

}  // namespace rockfit::core
