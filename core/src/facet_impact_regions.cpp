#include "rockfit/core/facet_impact_regions.hpp"

#include <cmath>
#include <deque>
#include <map>
#include <optional>
#include <utility>
#include <string>

#include <Eigen/LU>

#include "rockfit/core/checks.hpp"
#include "rockfit/core/errors.hpp"

namespace rockfit::core {
namespace {

void RequireCount(int n, const char* name) {
  if (n < 2 || n > kFacetRegionMaxPoints) {
    throw InvalidArgument(std::string("regions: ") + name + " must be between 2 and " + std::to_string(kFacetRegionMaxPoints) +
                          " grid points, got " + std::to_string(n));
  }
}

// n points from lo to hi; lo + (hi − lo)·k/(n − 1) hits both ends (and 0 of a symmetric range) exactly.
std::vector<double> Axis(double lo, double hi, int n) {
  std::vector<double> values(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) values[static_cast<std::size_t>(k)] = lo + (hi - lo) * k / (n - 1);
  values.back() = hi;
  return values;
}

// Where f changes from ≤ 0 to > 0 between two points (f_p ≤ 0 < f_q or the reverse), by linear interpolation.
// The two points are taken in a fixed order, so the squares on both sides of a side compute the same point
// bit for bit (ChainSegments joins the pieces by exact equality).
Eigen::Vector2d Crossing(const Eigen::Vector2d& p, double f_p, const Eigen::Vector2d& q, double f_q) {
  if (q.x() < p.x() || (q.x() == p.x() && q.y() < p.y())) return Crossing(q, f_q, p, f_p);
  const double t = f_p / (f_p - f_q);  // f_p and f_q lie on different sides of 0, so f_p ≠ f_q
  return p + t * (q - p);
}

}  // namespace

void FacetRegionOptions::Validate() const {
  RequireFinite(tau, "regions: τ");
  if (!w_minus_B.allFinite() || w_minus_B.norm() == 0.0) throw InvalidArgument("regions: ω⁻ must be finite and non-zero");
  RequireIncreasingRange(lambda_lat_min, lambda_lat_max, "regions: λ_lat");
  RequireIncreasingRange(lambda_lon_min, lambda_lon_max, "regions: λ_lon");
  RequireCount(n_lat, "λ_lat");
  RequireCount(n_lon, "λ_lon");
}

double FacetCandidateDeterminant(const Block& block, int pivot_b, int a, double lambda_lat, double lambda_lon,
                                 FacetTauRule rule) {
  const Eigen::Vector3d p_C = block.p_BC_B();
  const Eigen::Vector3d p_R = FacetResultantPoint(block, pivot_b, lambda_lat, lambda_lon);  // (21)
  const Eigen::Matrix3d M =
      block.inertia_C_B() - block.mass() * SkewOf(p_R, p_C) * SkewOf(block.p_BV_B(a), p_C);  // (18)
  if (rule == FacetTauRule::kFixed) return M.determinant();
  // (18) with (24): unknowns (ω⁺_x, ω⁺_y, τ), columns M e_x, M e_y and −u_z.
  Eigen::Matrix3d system;
  system.col(0) = M.col(0);
  system.col(1) = M.col(1);
  system.col(2) = -Eigen::Vector3d::UnitZ();
  return system.determinant();
}

std::vector<ContourSegment> ZeroContour(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& f,
                                 const std::vector<char>& valid) {
  const std::size_t nx = x.size(), ny = y.size();
  if (f.size() != nx * ny || valid.size() != nx * ny) throw InvalidArgument("ZeroContour: field size differs from the grid");
  std::vector<ContourSegment> segments;
  if (nx < 2 || ny < 2) return segments;
  for (std::size_t j = 0; j + 1 < ny; ++j) {
    for (std::size_t i = 0; i + 1 < nx; ++i) {
      // Corners counter-clockwise from the lower left; side s joins corner s and corner s+1.
      const std::size_t idx[4] = {j * nx + i, j * nx + i + 1, (j + 1) * nx + i + 1, (j + 1) * nx + i};
      if (!valid[idx[0]] || !valid[idx[1]] || !valid[idx[2]] || !valid[idx[3]]) continue;
      const Eigen::Vector2d p[4] = {{x[i], y[j]}, {x[i + 1], y[j]}, {x[i + 1], y[j + 1]}, {x[i], y[j + 1]}};
      const double v[4] = {f[idx[0]], f[idx[1]], f[idx[2]], f[idx[3]]};
      bool inside[4];
      for (int c = 0; c < 4; ++c) inside[c] = v[c] <= 0.0;
      Eigen::Vector2d cross[4];
      int sides[4];
      int n = 0;
      for (int s = 0; s < 4; ++s) {
        const int t = (s + 1) % 4;
        if (inside[s] != inside[t]) {
          cross[s] = Crossing(p[s], v[s], p[t], v[t]);
          sides[n++] = s;
        }
      }
      if (n == 2) {
        segments.push_back({cross[sides[0]], cross[sides[1]]});
      } else if (n == 4) {
        // Saddle: corners 0 and 2 on one side, 1 and 3 on the other. The mean decides which pair connects.
        const bool centre_inside = 0.25 * (v[0] + v[1] + v[2] + v[3]) <= 0.0;
        if (centre_inside == inside[0]) {  // 0 and 2 connected: cut off corners 1 and 3
          segments.push_back({cross[0], cross[1]});
          segments.push_back({cross[2], cross[3]});
        } else {  // cut off corners 0 and 2
          segments.push_back({cross[3], cross[0]});
          segments.push_back({cross[1], cross[2]});
        }
      }
    }
  }
  return segments;
}

FacetRegionGrid EvaluateFacetRegions(const Block& block, const FacetRegionOptions& options) {
  options.Validate();
  FacetRegionGrid grid;
  grid.lambda_lat = Axis(options.lambda_lat_min, options.lambda_lat_max, options.n_lat);
  grid.lambda_lon = Axis(options.lambda_lon_min, options.lambda_lon_max, options.n_lon);
  const std::size_t n = grid.lambda_lat.size() * grid.lambda_lon.size();
  grid.cells.resize(n);
  std::vector<double> delta_energy(n, 0.0);
  std::vector<char> has_energy(n, 0);

  FacetImpactParameters params;
  params.tau_rule = options.tau_rule;
  params.tau = options.tau;
  std::size_t k = 0;
  for (double lon : grid.lambda_lon) {
    for (double lat : grid.lambda_lat) {
      params.lambda_lat = lat;
      params.lambda_lon = lon;
      const ImpactOutcome out = FacetImpact(block, options.pivot_b, options.w_minus_B, params);
      FacetRegionCell& cell = grid.cells[k];
      cell.status = out.status;
      cell.contact = out.contact_after;
      cell.has_energy = out.status == ImpactStatus::kOk;
      cell.delta_energy_J = cell.has_energy ? out.delta_energy_J : 0.0;  // (26)
      delta_energy[k] = cell.delta_energy_J;
      has_energy[k] = cell.has_energy ? 1 : 0;
      ++k;
    }
  }
  grid.energy_zero = ZeroContour(grid.lambda_lat, grid.lambda_lon, delta_energy, has_energy);

  const std::vector<char> everywhere(n, 1);
  std::vector<double> det(n);
  for (int a = 1; a <= 4; ++a) {
    k = 0;
    for (double lon : grid.lambda_lon) {
      for (double lat : grid.lambda_lat) {
        det[k++] = FacetCandidateDeterminant(block, options.pivot_b, a, lat, lon, options.tau_rule);
      }
    }
    const std::vector<ContourSegment> curve = ZeroContour(grid.lambda_lat, grid.lambda_lon, det, everywhere);
    grid.singular.insert(grid.singular.end(), curve.begin(), curve.end());
  }
  return grid;
}

std::vector<std::vector<Eigen::Vector2d>> ChainSegments(const std::vector<ContourSegment>& segments) {
  using Key = std::pair<double, double>;
  std::map<Key, std::vector<std::size_t>> ends;
  for (std::size_t s = 0; s < segments.size(); ++s) {
    ends[{segments[s].from.x(), segments[s].from.y()}].push_back(s);
    ends[{segments[s].to.x(), segments[s].to.y()}].push_back(s);
  }
  std::vector<char> used(segments.size(), 0);
  // A segment of zero length (a corner with f = 0 exactly) adds nothing to a drawing and would start a line of
  // its own.
  for (std::size_t s = 0; s < segments.size(); ++s) used[s] = segments[s].from == segments[s].to ? 1 : 0;
  // The other end of segment s, seen from point p.
  const auto other = [&](std::size_t s, const Eigen::Vector2d& p) { return segments[s].from == p ? segments[s].to : segments[s].from; };
  const auto next_unused = [&](const Eigen::Vector2d& p) -> std::optional<std::size_t> {
    for (std::size_t s : ends[{p.x(), p.y()}]) {
      if (!used[s]) return s;
    }
    return std::nullopt;
  };
  std::vector<std::vector<Eigen::Vector2d>> lines;
  for (std::size_t start = 0; start < segments.size(); ++start) {
    if (used[start]) continue;
    used[start] = 1;
    std::deque<Eigen::Vector2d> line{segments[start].from, segments[start].to};
    while (const auto s = next_unused(line.back())) {
      used[*s] = 1;
      line.push_back(other(*s, line.back()));
    }
    while (const auto s = next_unused(line.front())) {
      used[*s] = 1;
      line.push_front(other(*s, line.front()));
    }
    lines.emplace_back(line.begin(), line.end());
  }
  return lines;
}

std::string FacetRegionLabel(const FacetRegionCell& cell) {
  if (cell.status != ImpactStatus::kOk) return ToString(cell.status);
  if (cell.contact.first == 0) return "rest";
  return cell.contact.ToString();
}

}  // namespace rockfit::core
