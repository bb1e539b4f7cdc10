// The facet-impact regions of the paper's Fig. 11 over a grid of (λ_lat, λ_lon): the post-impact contact or
// status of FacetImpact (18)+(21)–(24) at every grid point, ΔE of (26) where the impact has an outcome, and
// the curves ΔE = 0 and "(18) singular" as line segments. Pure: no files, no
// drawing (`rockfit plot regions` in tools/src/plot_regions.cpp draws it).
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rockfit/core/block.hpp"
#include "rockfit/core/contact.hpp"
#include "rockfit/core/facet_impact.hpp"
#include "rockfit/core/general_impact_map.hpp"

namespace rockfit::core {

struct FacetRegionOptions {
  int pivot_b = 2;  // the pre-impact pivot edge V_{b−1}V_b (b taken cyclically)
  Eigen::Vector3d w_minus_B = Eigen::Vector3d(0.0, 1.0, 0.0);  // [rad/s], body frame (W = B at a facet impact)
  FacetTauRule tau_rule = FacetTauRule::kNoSpin;  // kNoSpin: the unified map (24)
  double tau = 0.0;                                           // [N·m·s], used with kFixed
  double lambda_lat_min = -2.0, lambda_lat_max = 2.0;         // horizontal axis
  double lambda_lon_min = -2.0, lambda_lon_max = 2.0;         // vertical axis
  int n_lat = 201, n_lon = 201;                               // grid points per axis, ≥ 2
  // Throws InvalidArgument naming the field: non-finite values, empty ranges, fewer than 2 or more than
  // kFacetRegionMaxPoints points per axis, ω⁻ = 0.
  void Validate() const;
};
inline constexpr int kFacetRegionMaxPoints = 2001;  // per axis: 4·10⁶ impacts, about a few seconds

// One grid point: the outcome of FacetImpact there. delta_energy_J is meaningful only when has_energy
// (status kOk); otherwise it is zero.
struct FacetRegionCell {
  ImpactStatus status = ImpactStatus::kOk;
  Contact contact;  // kOk only: vertex, edge, or empty (the impact stops the block on its base)
  bool has_energy = false;
  double delta_energy_J = 0.0;  // (26)
};

// A straight piece of a curve in the (λ_lat, λ_lon) plane.
struct ContourSegment {
  Eigen::Vector2d from, to;  // (λ_lat, λ_lon)
};

struct FacetRegionGrid {
  std::vector<double> lambda_lat;  // n_lat values, ascending, end points exact
  std::vector<double> lambda_lon;  // n_lon values
  std::vector<FacetRegionCell> cells;   // row-major: cells[j·n_lat + i] at (lambda_lat[i], lambda_lon[j])
  // ΔE = 0 of (26) between neighbouring grid points that both have an outcome (linear interpolation).
  std::vector<ContourSegment> energy_zero;
  // Where the system that FacetImpact solves for a candidate vertex V_a is singular: det = 0 of
  // Θ − m R_R R_a (18) (fixed τ) or of the (ω⁺_x, ω⁺_y, τ) system of (18)+(24) (no-spin); all four a.
  std::vector<ContourSegment> singular;
  const FacetRegionCell& at(int i_lat, int j_lon) const { return cells[static_cast<std::size_t>(j_lon) * lambda_lat.size() + i_lat]; }
};

// Evaluates the facet map at every grid point. Throws InvalidArgument for invalid options.
FacetRegionGrid EvaluateFacetRegions(const Block& block, const FacetRegionOptions& options);

// The determinant whose zero makes candidate V_a singular in FacetImpact (see FacetRegionGrid::singular).
double FacetCandidateDeterminant(const Block& block, int pivot_b, int a, double lambda_lat, double lambda_lon,
                                 FacetTauRule rule);

// The sign-change curve f = 0 of a field on the grid by marching squares: a square of four neighbouring
// points all marked `valid` gets one segment per pair of its sides on which f ≤ 0 changes to f > 0 (two at a
// saddle, separated by the mean of the corners). Points where f ≤ 0 lie on one side, f > 0 on the other.
std::vector<ContourSegment> ZeroContour(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& f,
                                 const std::vector<char>& valid);

// Joins segments that share an end point exactly (as ZeroContour produces them) into polylines, so that a
// dashed line keeps its pattern. Every segment of non-zero length appears in exactly one polyline.
std::vector<std::vector<Eigen::Vector2d>> ChainSegments(const std::vector<ContourSegment>& segments);

// "V3", "V3V4", "rest" (empty contact), "infeasible", "ambiguous" or "singular".
std::string FacetRegionLabel(const FacetRegionCell& cell);

}  // namespace rockfit::core
