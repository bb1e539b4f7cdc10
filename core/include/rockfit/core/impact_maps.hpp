// Impact maps of Várkonyi, Kocsis & Ther (2021): planar AVRFs (3)–(6), the general map (18), the edge
// map (19)–(20), the facet map (18)+(21) with feasibility (22)–(23), the unified facet map with the
// no-spin postulate (24), energy (26) and the bounds (25), (27). DESIGN §3, including its errata.
//
// Every function is pure: it takes a const Block and the impact configuration and returns a value.
// Numerical trouble is a status, never a NaN.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "rockfit/core/block.hpp"

namespace rockfit::core {

enum class ImpactStatus { kOk, kInfeasible, kAmbiguous, kSingular };
// "ok", "infeasible", "ambiguous", "singular".
const char* ToString(ImpactStatus status);

// Base vertices in contact with the ground: one vertex (second == 0) or a base edge.
struct Contact {
  int first = 0;
  int second = 0;
  static Contact Vertex(int k) { return {Block::WrapVertex(k), 0}; }
  // The edge between two neighbouring vertices, stored in cyclic order (V1V2, V2V3, V3V4, V4V1).
  static Contact Edge(int i, int j);
  bool is_vertex() const { return first != 0 && second == 0; }
  bool is_edge() const { return first != 0 && second != 0; }
  // "V4" or "V3V4"; "none" when empty.
  std::string ToString() const;
  bool operator==(const Contact& other) const { return first == other.first && second == other.second; }
  bool operator!=(const Contact& other) const { return !(*this == other); }
};

// ---------------------------------------------------------------- planar impacts (Sect. 2)

// A planar rocking block: mass m, moment of inertia θ about the COM (planar), COM height h and half-length b
// of the impacting base.
struct PlanarBlock {
  double mass_kg;
  double theta_kg_m2;
  double h_m;
  double b_m;
};
// Rocking in the xz plane (about y): θ = Θ_yy, b = b1.
PlanarBlock PlanarBlockAboutY(const Block& block);
// Rocking in the yz plane (about x): θ = Θ_xx, b = b2.
PlanarBlock PlanarBlockAboutX(const Block& block);

double AvrfHousner(const PlanarBlock& p);                   // (3)
double AvrfKalliontzis(const PlanarBlock& p, double v);     // (4)
double AvrfTherKollar(const PlanarBlock& p);                // (5)
double AvrfChatzis(const PlanarBlock& p, double lambda);    // (6)
// Inverse of (6): the λ whose AVRF is r. Defined for every finite r ≠ −1.
double LambdaFromAvrf(const PlanarBlock& p, double r);

// ---------------------------------------------------------------- general map (Sect. 4.3)

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

// R_x of (14): the matrix with R_x·ω = ω × (p_C − p_x).
Eigen::Matrix3d SkewOf(const Eigen::Vector3d& p_x, const Eigen::Vector3d& p_C);

struct MapResult {
  ImpactStatus status = ImpactStatus::kOk;  // kOk or kSingular
  Eigen::Vector3d w_plus = Eigen::Vector3d::Zero();
};
// (18): ω⁺ = (Θ − m R_R R_a)⁻¹[(Θ − m R_R R_b) ω⁻ + τ u_z]. kSingular (and w_plus = 0) when the matrix
// to invert is singular to working precision.
MapResult GeneralImpactMap(const ImpactGeometry& g, const Eigen::Vector3d& w_minus, double tau);

// Kinetic energy of rotation ω about the fixed point p_x: ½ ωᵀ(Θ + m R_xᵀR_x)ω (Sect. 4.8).
double KineticEnergyAbout(const ImpactGeometry& g, const Eigen::Vector3d& p_x, const Eigen::Vector3d& w);

// ---------------------------------------------------------------- edge and facet impacts

enum class FacetTauRule { kNoSpin, kFixed };
// "no-spin" or "fixed".
const char* ToString(FacetTauRule rule);

struct EdgeImpactParameters {
  double lambda = 1.0;  // position of R along V_bV_a, (19)
  double tau = 0.0;     // vertical angular impulse [N·m·s]
};

struct FacetImpactParameters {
  double lambda_lat = 0.0;  // (21)
  double lambda_lon = 1.0;  // (21)
  FacetTauRule tau_rule = FacetTauRule::kNoSpin;  // kNoSpin: τ from (24); kFixed: τ below
  double tau = 0.0;         // [N·m·s], used with kFixed
};

// One candidate post-impact vertex of a facet impact.
struct FacetCandidate {
  Contact contact;
  ImpactStatus status = ImpactStatus::kOk;  // kOk or kSingular
  bool feasible = false;                    // (22) and (23) hold
  Eigen::Vector3d w_plus = Eigen::Vector3d::Zero();
  double tau = 0.0;
};

struct ImpactOutcome {
  ImpactStatus status = ImpactStatus::kOk;
  Eigen::Vector3d w_minus_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d w_plus_W = Eigen::Vector3d::Zero();  // zero unless status is kOk
  Eigen::Vector3d w_plus_B = Eigen::Vector3d::Zero();
  double tau = 0.0;  // the τ used [N·m·s]
  Contact contact_before;
  Contact contact_after;
  double energy_before_J = 0.0;
  double energy_after_J = 0.0;
  double delta_energy_J = 0.0;           // (26)
  bool within_geometric_bounds = false;  // (25) for edge impacts, (27) for facet impacts
  bool energy_nonincreasing = false;     // (26): ΔE ≤ 0 (within round-off)
  std::vector<FacetCandidate> candidates;  // facet impacts: every candidate vertex
};

// R_WB of a block standing on the edge V_bV_a with the rest of its base lifted by `tilt_rad` ≥ 0
// (rotation about that edge), yaw chosen so that the edge keeps its body direction in the ground plane.
Eigen::Matrix3d EdgeImpactAttitude(const Block& block, int pivot, int landing, double tilt_rad);

// Edge impact (19)–(20): rocking about V_b = `pivot` until the edge V_bV_a (a = `landing`, a neighbour of b)
// hits the ground. R_WB is the attitude at the impact, w_minus_W the pre-impact angular velocity in W.
// After the impact the block rocks about V_a if the vertical velocity of V_b is positive, otherwise it keeps
// edge contact V_aV_b. Throws InvalidArgument if pivot and landing are not neighbours.
ImpactOutcome EdgeImpact(const Block& block, const Eigen::Matrix3d& R_WB, int pivot, int landing,
                         const Eigen::Vector3d& w_minus_W, const EdgeImpactParameters& params);
// The λ at which Θ − m R_R R_a of the edge map is singular (real roots of its determinant, a polynomial in λ).
std::vector<double> EdgeImpactSingularLambdas(const Block& block, const Eigen::Matrix3d& R_WB, int pivot, int landing);

// Facet impact (18)+(21) of the flat block after rocking about the edge V_{b−1}V_b, b = `pivot_b`.
// w_minus_B is in the body frame (W and B coincide up to a yaw, to which the map is invariant).
// kNoSpin solves (18) with (24) for (ω⁺_x, ω⁺_y, τ); kFixed tests every candidate against (22)–(23) and
// returns the unique feasible one or kInfeasible / kAmbiguous with all candidates listed.
ImpactOutcome FacetImpact(const Block& block, int pivot_b, const Eigen::Vector3d& w_minus_B,
                          const FacetImpactParameters& params);

bool WithinEdgeBounds(double lambda);                           // (25)
bool WithinFacetBounds(double lambda_lat, double lambda_lon);   // (27)

}  // namespace rockfit::core
