// EvaluateFacetRegions (the paper's Fig. 11 over a grid), ZeroContour and ChainSegments: against the errata sign
// rule of docs/design.md §3, the mirror symmetry of the block, the planar map (6), the definition of the contour and
// a closed form of the determinant of (18).
#include "rockfit/core/facet_impact_regions.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/core/planar_avrf.hpp"

namespace rockfit::core {
namespace {

Block Fig11Block() { return Block::FromMass(0.05, 0.03, 0.20, 1.0); }  // Sect. 4.5, m = 1 kg

// 1 rad/s falling onto the base about V_{b−1}V_b: a positive multiple of r_b − r_{b−1} (core/README.md).
Eigen::Vector3d Falling(const Block& block, int b) { return (block.p_BV_B(b) - block.p_BV_B(b - 1)).normalized(); }

FacetRegionOptions Options(const Block& block, int b, int points) {
  FacetRegionOptions o;
  o.pivot_b = b;
  o.w_minus_B = Falling(block, b);
  o.n_lat = o.n_lon = points;
  return o;
}

TEST(FacetImpactRegions, NoSpinClassificationEqualsTheErrataSignRuleEverywhere) {
  const Block block = Fig11Block();
  for (int b = 1; b <= 4; ++b) {
    const FacetRegionGrid grid = EvaluateFacetRegions(block, Options(block, b, 41));
    ASSERT_EQ(grid.lambda_lat[20], 0.0);  // the grid hits λ_lat = 0 exactly
    for (int j = 0; j < 41; ++j) {
      for (int i = 0; i < 41; ++i) {
        const double lat = grid.lambda_lat[i];
        const FacetRegionCell& cell = grid.at(i, j);
        ASSERT_EQ(cell.status, ImpactStatus::kOk) << "b=" << b << " at " << lat << "," << grid.lambda_lon[j];
        const Contact expected = lat > 0.0   ? Contact::Vertex(b + 2)
                                 : lat < 0.0 ? Contact::Vertex(b + 1)
                                             : Contact::Edge(b + 1, b + 2);  // docs/design.md §3 errata
        EXPECT_EQ(cell.contact, expected) << "b=" << b << " at " << lat << "," << grid.lambda_lon[j];
        EXPECT_TRUE(cell.has_energy);
      }
    }
  }
}

TEST(FacetImpactRegions, FixedTauOfTheFig11BlockHasInfeasibleAndAmbiguousCells) {
  const Block block = Fig11Block();
  for (double tau : {1e-4, -1e-4}) {  // N·m·s
    FacetRegionOptions o = Options(block, 2, 61);
    o.tau_rule = FacetTauRule::kFixed;
    o.tau = tau;
    const FacetRegionGrid grid = EvaluateFacetRegions(block, o);
    const auto count = [&](ImpactStatus s) {
      return std::count_if(grid.cells.begin(), grid.cells.end(), [s](const FacetRegionCell& c) { return c.status == s; });
    };
    EXPECT_GT(count(ImpactStatus::kInfeasible), 0) << "τ = " << tau;
    EXPECT_GT(count(ImpactStatus::kAmbiguous), 0) << "τ = " << tau;
    EXPECT_GT(count(ImpactStatus::kOk), 0) << "τ = " << tau;
    for (const FacetRegionCell& c : grid.cells) EXPECT_EQ(c.has_energy, c.status == ImpactStatus::kOk);
  }
}

// Reflecting the block in its xz plane swaps V1↔V2 and V3↔V4, keeps the pivot edge V1V2 and ω⁻ = (0, ω, 0)
// (an axial vector), and changes the signs of λ_lat (along V2 − V1) and of τ (about u_z).
TEST(FacetImpactRegions, FixedTauRegionsAreMirrorImagesWhenTauChangesSign) {
  const Block block = Fig11Block();
  FacetRegionOptions o = Options(block, 2, 41);
  o.tau_rule = FacetTauRule::kFixed;
  o.tau = 1e-4;
  const FacetRegionGrid plus = EvaluateFacetRegions(block, o);
  o.tau = -1e-4;
  const FacetRegionGrid minus = EvaluateFacetRegions(block, o);
  const auto mirror = [](Contact c) {
    const auto swap = [](int k) { return k == 0 ? 0 : (k == 1 ? 2 : k == 2 ? 1 : k == 3 ? 4 : 3); };
    if (c.is_edge()) return Contact::Edge(swap(c.first), swap(c.second));
    return c.is_vertex() ? Contact::Vertex(swap(c.first)) : c;
  };
  for (int j = 0; j < 41; ++j) {
    for (int i = 0; i < 41; ++i) {
      const FacetRegionCell& a = plus.at(i, j);
      const FacetRegionCell& m = minus.at(40 - i, j);
      ASSERT_EQ(a.status, m.status) << "at " << plus.lambda_lat[i] << "," << plus.lambda_lon[j];
      EXPECT_EQ(mirror(a.contact), m.contact);
      EXPECT_NEAR(a.delta_energy_J, m.delta_energy_J, 1e-12 * block.mass());
    }
  }
}

// At λ_lat = 0 the facet map is the planar map (6) with λ = λ_lon (docs/design.md §3): ω⁺ = r ω⁻ about the opposite edge,
// whose moment of inertia equals that about the pivot edge, so ΔE = (r² − 1)·E⁻.
TEST(FacetImpactRegions, EnergyAtZeroLambdaLatIsThatOfThePlanarMap) {
  const Block block = Fig11Block();
  const FacetRegionGrid grid = EvaluateFacetRegions(block, Options(block, 2, 41));
  const PlanarBlock planar = PlanarBlockAboutY(block);
  const double inertia_edge = planar.theta_kg_m2 + planar.mass_kg * (planar.b_m * planar.b_m + planar.h_m * planar.h_m);
  const double energy_before_J = 0.5 * inertia_edge * 1.0;  // |ω⁻| = 1 rad/s
  constexpr double kEnergyTolJ = 1e-12;  // round-off of (18) and of two quadratic forms at E⁻ ≈ 0.015 J
  for (int j = 0; j < 41; ++j) {
    const double r = AvrfChatzis(planar, grid.lambda_lon[j]);  // (6)
    EXPECT_NEAR(grid.at(20, j).delta_energy_J, (r * r - 1.0) * energy_before_J, kEnergyTolJ) << grid.lambda_lon[j];
  }
  // The curve ΔE = 0 crosses λ_lat = 0 where (6) gives r = 1, to the accuracy of linear interpolation.
  const double lambda_r1 = LambdaFromAvrf(planar, 1.0);
  const double spacing = grid.lambda_lon[1] - grid.lambda_lon[0];
  int crossings = 0;
  for (const ContourSegment& s : grid.energy_zero) {
    for (const Eigen::Vector2d& p : {s.from, s.to}) {
      if (p.x() != 0.0) continue;
      ++crossings;
      EXPECT_NEAR(p.y(), lambda_r1, 0.1 * spacing);
    }
  }
  EXPECT_GE(crossings, 2);  // shared by the squares on both sides of λ_lat = 0 (more where ΔE = 0 at a grid point)
}

// Every end point of the ΔE = 0 contour lies on a link between two neighbouring grid points with ΔE ≤ 0 at one
// and ΔE > 0 at the other, and every such link (inside four points with an outcome) carries an end point.
void ExpectContourSeparates(const FacetRegionGrid& grid) {
  const std::size_t nx = grid.lambda_lat.size(), ny = grid.lambda_lon.size();
  const auto side = [&](std::size_t i, std::size_t j) { return grid.at(int(i), int(j)).delta_energy_J <= 0.0; };
  const auto valid = [&](std::size_t i, std::size_t j) { return grid.at(int(i), int(j)).has_energy; };
  const auto index_of = [](const std::vector<double>& axis, double v) {
    const auto it = std::find(axis.begin(), axis.end(), v);
    return it == axis.end() ? std::ptrdiff_t(-1) : it - axis.begin();
  };
  // Links with an end point: (i, j, horizontal?). An end point exactly at a grid point lies on up to four links.
  std::vector<std::array<std::ptrdiff_t, 3>> carried;
  for (const ContourSegment& s : grid.energy_zero) {
    for (const Eigen::Vector2d& p : {s.from, s.to}) {
      const std::ptrdiff_t ix = index_of(grid.lambda_lat, p.x()), jy = index_of(grid.lambda_lon, p.y());
      ASSERT_TRUE(ix >= 0 || jy >= 0) << "end point off the grid lines: " << p.transpose();
      bool on_changing_link = false;
      for (std::size_t j = 0; ix >= 0 && j + 1 < ny; ++j) {  // vertical links through p
        if (p.y() < grid.lambda_lon[j] || p.y() > grid.lambda_lon[j + 1]) continue;
        if (valid(ix, j) && valid(ix, j + 1) && side(ix, j) != side(ix, j + 1)) {
          on_changing_link = true;
          carried.push_back({ix, std::ptrdiff_t(j), 0});
        }
      }
      for (std::size_t i = 0; jy >= 0 && i + 1 < nx; ++i) {  // horizontal links through p
        if (p.x() < grid.lambda_lat[i] || p.x() > grid.lambda_lat[i + 1]) continue;
        if (valid(i, jy) && valid(i + 1, jy) && side(i, jy) != side(i + 1, jy)) {
          on_changing_link = true;
          carried.push_back({std::ptrdiff_t(i), jy, 1});
        }
      }
      EXPECT_TRUE(on_changing_link) << p.transpose();
    }
  }
  const auto has = [&](std::ptrdiff_t i, std::ptrdiff_t j, std::ptrdiff_t h) {
    return std::find(carried.begin(), carried.end(), std::array<std::ptrdiff_t, 3>{i, j, h}) != carried.end();
  };
  const auto square_valid = [&](std::size_t i, std::size_t j) {
    return i + 1 < nx && j + 1 < ny && valid(i, j) && valid(i + 1, j) && valid(i, j + 1) && valid(i + 1, j + 1);
  };
  int changing = 0;
  for (std::size_t j = 0; j < ny; ++j) {
    for (std::size_t i = 0; i < nx; ++i) {
      const bool in_square_h = square_valid(i, j) || (j > 0 && square_valid(i, j - 1));
      if (i + 1 < nx && in_square_h && side(i, j) != side(i + 1, j)) {
        ++changing;
        EXPECT_TRUE(has(i, j, 1)) << "horizontal link at " << i << "," << j;
      }
      const bool in_square_v = square_valid(i, j) || (i > 0 && square_valid(i - 1, j));
      if (j + 1 < ny && in_square_v && side(i, j) != side(i, j + 1)) {
        ++changing;
        EXPECT_TRUE(has(i, j, 0)) << "vertical link at " << i << "," << j;
      }
    }
  }
  EXPECT_GT(changing, 10);  // the bound crosses the plotted range (Fig. 11)
}

TEST(FacetImpactRegions, EnergyContourSeparatesEnergyLossFromGain) {
  const Block block = Fig11Block();
  ExpectContourSeparates(EvaluateFacetRegions(block, Options(block, 2, 41)));
  FacetRegionOptions fixed = Options(block, 2, 41);
  fixed.tau_rule = FacetTauRule::kFixed;
  fixed.tau = 1e-4;
  ExpectContourSeparates(EvaluateFacetRegions(block, fixed));
}

// With u = r_R − r_c and v = r_a − r_c, R_R R_a = v uᵀ − (u·v) I, so Θ − m R_R R_a = A − m v uᵀ with
// A = Θ + m (u·v) I diagonal, and det = det(A)·(1 − m uᵀA⁻¹v) (matrix determinant lemma).
double ClosedFormDeterminant(const Block& block, int b, int a, double lat, double lon) {
  const Eigen::Vector3d u = FacetResultantPoint(block, b, lat, lon) - block.p_BC_B();
  const Eigen::Vector3d v = block.p_BV_B(a) - block.p_BC_B();
  const Eigen::Vector3d A = block.inertia_C_B().diagonal().array() + block.mass() * u.dot(v);
  return A.prod() * (1.0 - block.mass() * (u.array() * v.array() / A.array()).sum());
}

TEST(FacetImpactRegions, DeterminantOfEighteenMatchesTheDeterminantLemma) {
  const Block block = Fig11Block();
  std::mt19937 rng(20211);
  std::uniform_real_distribution<double> lambda(-3.0, 3.0);
  for (int k = 0; k < 200; ++k) {
    const double lat = lambda(rng), lon = lambda(rng);
    const int b = 1 + k % 4, a = 1 + (k / 4) % 4;
    const double expected = ClosedFormDeterminant(block, b, a, lat, lon);
    const double scale = std::pow(block.inertia_C_B().diagonal().maxCoeff(), 3);
    EXPECT_NEAR(FacetCandidateDeterminant(block, b, a, lat, lon, FacetTauRule::kFixed), expected, 1e-12 * scale);
  }
}

TEST(FacetImpactRegions, SingularCurvesLieWhereACandidateDeterminantVanishes) {
  const Block block = Fig11Block();
  FacetRegionOptions o = Options(block, 2, 41);
  o.tau_rule = FacetTauRule::kFixed;
  o.tau = 1e-4;
  const FacetRegionGrid grid = EvaluateFacetRegions(block, o);
  ASSERT_FALSE(grid.singular.empty());  // Fig. 11b shows dash-dotted lines within [−2, 2]²
  const double scale = std::pow(block.inertia_C_B().diagonal().maxCoeff(), 3);
  for (const ContourSegment& s : grid.singular) {
    double smallest = INFINITY;
    for (int a = 1; a <= 4; ++a) smallest = std::min(smallest, std::abs(ClosedFormDeterminant(block, 2, a, s.from.x(), s.from.y())));
    EXPECT_LT(smallest, 1e-3 * scale) << s.from.transpose();
  }
}

TEST(ZeroContour, CircleIsOneClosedPolylineOnTheCircle) {
  std::vector<double> x, y;
  for (int k = 0; k <= 80; ++k) x.push_back(-2.0 + 4.0 * k / 80);
  y = x;
  std::vector<double> f;
  for (double yy : y) {
    for (double xx : x) f.push_back(xx * xx + yy * yy - 1.0);
  }
  const std::vector<ContourSegment> segments = ZeroContour(x, y, f, std::vector<char>(f.size(), 1));
  ASSERT_GT(segments.size(), 40u);
  constexpr double kInterpolationTol = 2e-3;  // linear interpolation of a quadratic over a spacing of 0.05
  for (const ContourSegment& s : segments) {
    EXPECT_NEAR(s.from.norm(), 1.0, kInterpolationTol);
    EXPECT_NEAR(s.to.norm(), 1.0, kInterpolationTol);
  }
  // The circle passes exactly through the grid points (±1, 0) and (0, ±1): squares touching one of them only
  // at a corner give segments of zero length, which the chain leaves out.
  const auto proper = std::count_if(segments.begin(), segments.end(), [](const ContourSegment& s) { return s.from != s.to; });
  EXPECT_LT(proper, static_cast<std::ptrdiff_t>(segments.size()));
  const auto lines = ChainSegments(segments);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(static_cast<std::ptrdiff_t>(lines[0].size()), proper + 1);
  EXPECT_EQ(lines[0].front(), lines[0].back());
}

TEST(ZeroContour, InvalidPointsCutTheContour) {
  const std::vector<double> x{0.0, 1.0, 2.0}, y{0.0, 1.0};
  const std::vector<double> f{-1.0, 1.0, 3.0, -1.0, 1.0, 3.0};  // f = 2x − 1: zero at x = 0.5
  EXPECT_EQ(ZeroContour(x, y, f, std::vector<char>(6, 1)).size(), 1u);
  const auto s = ZeroContour(x, y, f, std::vector<char>(6, 1)).front();
  EXPECT_DOUBLE_EQ(s.from.x(), 0.5);
  EXPECT_DOUBLE_EQ(s.to.x(), 0.5);
  EXPECT_TRUE(ZeroContour(x, y, f, {1, 1, 1, 0, 1, 1}).empty());
}

TEST(FacetImpactRegions, InvalidOptionsAreRejected) {
  const Block block = Fig11Block();
  FacetRegionOptions o = Options(block, 2, 11);
  o.lambda_lat_min = 1.0;
  o.lambda_lat_max = 1.0;
  EXPECT_THROW(EvaluateFacetRegions(block, o), InvalidArgument);
  o = Options(block, 2, 1);
  EXPECT_THROW(EvaluateFacetRegions(block, o), InvalidArgument);
  o = Options(block, 2, 11);
  o.tau = NAN;
  EXPECT_THROW(EvaluateFacetRegions(block, o), InvalidArgument);
  o = Options(block, 2, 11);
  o.w_minus_B.setZero();
  EXPECT_THROW(EvaluateFacetRegions(block, o), InvalidArgument);
}

TEST(FacetImpactRegions, LabelsNameContactsAndStatuses) {
  EXPECT_EQ(FacetRegionLabel({ImpactStatus::kOk, Contact::Vertex(3), true, -1.0}), "V3");
  EXPECT_EQ(FacetRegionLabel({ImpactStatus::kOk, Contact::Edge(4, 3), true, -1.0}), "V3V4");
  EXPECT_EQ(FacetRegionLabel({ImpactStatus::kOk, Contact{}, true, -1.0}), "rest");
  EXPECT_EQ(FacetRegionLabel({ImpactStatus::kAmbiguous, Contact{}, false, 0.0}), "ambiguous");
  EXPECT_EQ(FacetRegionLabel({ImpactStatus::kInfeasible, Contact{}, false, 0.0}), "infeasible");
  EXPECT_EQ(FacetRegionLabel({ImpactStatus::kSingular, Contact{}, false, 0.0}), "singular");
}

}  // namespace
}  // namespace rockfit::core
