#include "rockfit/core/facet_impact.hpp"

#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "impact_equations.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/core/planar_avrf.hpp"

namespace rockfit::core {
namespace {

constexpr double kBalanceRelTol = 1e-12;  // (17) residual, the acceptance level of docs/design.md §12
constexpr double kVectorRelTol = 1e-12;   // two evaluations of the same linear map

Block Fig11Block() { return Block::FromMass(0.05, 0.03, 0.20, 1.0); }

// Falling onto the facet about V_{b−1}V_b: ω⁻ is a positive multiple of r_b − r_{b−1} (core/README.md).
// For b = 2 this is (0, +ω, 0). The paper's Fig. 11 writes ω⁻ = [0, −1, 0]ᵀ; in rockfit's frame (docs/design.md §2)
// that ω⁻ lifts the +x side off the ground (see FallingDirectionOfFig11IsPositiveY below).
Eigen::Vector3d FallingOmega(const Block& block, int b, double omega) {
  return omega * (block.p_BV_B(b) - block.p_BV_B(b - 1)).normalized();
}

ImpactGeometry GeometryOf(const Block& block, int b, int a, double lambda_lat, double lambda_lon) {
  ImpactGeometry g;
  g.mass_kg = block.mass();
  g.inertia_C = block.inertia_C_B();
  g.p_C = block.p_BC_B();
  g.p_b = block.p_BV_B(b);
  g.p_a = block.p_BV_B(a);
  // (21) written out independently of FacetResultantPoint.
  const Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  g.p_R = centroid + 0.5 * lambda_lon * (block.p_BV_B(b + 1) - block.p_BV_B(b)) +
          0.5 * lambda_lat * (block.p_BV_B(b) - block.p_BV_B(b - 1));
  return g;
}

// Grid values k·step for k = −n..n (exact zero in the middle).
double GridValue(int k, int n, double half_width) { return half_width * k / n; }

TEST(FacetTauRule, EveryNameThatToStringWritesReadsBackAndZeroMeansFixed) {
  for (const FacetTauRule rule : {FacetTauRule::kNoSpin, FacetTauRule::kFixed}) {
    FacetTauRule read = rule == FacetTauRule::kNoSpin ? FacetTauRule::kFixed : FacetTauRule::kNoSpin;
    ASSERT_TRUE(FromString(ToString(rule), &read)) << ToString(rule);
    EXPECT_EQ(read, rule);
  }
  FacetTauRule zero = FacetTauRule::kNoSpin;
  EXPECT_TRUE(FromString("zero", &zero));
  EXPECT_EQ(zero, FacetTauRule::kFixed);
  EXPECT_FALSE(FromString("Fixed", &zero));
  EXPECT_FALSE(FromString("", &zero));
}

TEST(FacetImpact, ResultantPointForPivotTwoIsLambdaLonB1LambdaLatB2) {
  const Block block = Fig11Block();
  EXPECT_LE((FacetResultantPoint(block, 2, 0.3, -0.7) - Eigen::Vector3d(-0.7 * 0.05, 0.3 * 0.03, 0.0)).norm(), 1e-17);
  // b = 3 (pivot edge V2V3 at y = +b2): λ_lon runs towards −y, λ_lat towards +x.
  EXPECT_LE((FacetResultantPoint(block, 3, 0.3, -0.7) - Eigen::Vector3d(0.3 * 0.05, 0.7 * 0.03, 0.0)).norm(), 1e-17);
}

TEST(FacetImpact, EveryCandidateSatisfiesTheImpulseMomentumBalance17) {
  const Block block = Fig11Block();
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int b = 1; b <= 4; ++b) {
    for (int k = 0; k < 25; ++k) {
      const double lat = u(rng), lon = u(rng);
      const Eigen::Vector3d w_minus = FallingOmega(block, b, 1.0) + Eigen::Vector3d(0.1 * u(rng), 0.1 * u(rng), 0.1 * u(rng));
      for (const FacetImpactParameters params :
           {FacetImpactParameters{lat, lon, FacetTauRule::kNoSpin, 0.0}, FacetImpactParameters{lat, lon, FacetTauRule::kFixed, 3e-4}}) {
        const ImpactOutcome out = FacetImpact(block, b, w_minus, params);
        ASSERT_EQ(out.candidates.size(), 4u);
        for (const FacetCandidate& c : out.candidates) {
          if (c.status != ImpactStatus::kOk) continue;
          const ImpactGeometry g = GeometryOf(block, b, c.contact.first, lat, lon);
          EXPECT_LE(testing::MomentumBalanceRelResidual(g, w_minus, c.w_plus, c.tau), kBalanceRelTol)
              << "b " << b << " a " << c.contact.first << " λ_lat " << lat << " λ_lon " << lon;
          if (params.tau_rule == FacetTauRule::kNoSpin) {
            EXPECT_EQ(c.w_plus.z(), 0.0);  // (24)
          } else {
            EXPECT_EQ(c.tau, 3e-4);
          }
        }
      }
    }
  }
}

TEST(FacetImpact, FeasibilityFlagsFollowConditions22And23) {
  const Block block = Fig11Block();
  const Eigen::Vector3d w_minus = FallingOmega(block, 2, 1.0);
  for (double lat : {-0.6, 0.0, 0.4}) {
    const ImpactOutcome out = FacetImpact(block, 2, w_minus, {lat, 0.8, FacetTauRule::kFixed, 1e-4});
    const Eigen::Vector3d v_minus = w_minus.cross(block.p_BC_B() - block.p_BV_B(2));  // (11)
    for (const FacetCandidate& c : out.candidates) {
      const Eigen::Vector3d v_plus = c.w_plus.cross(block.p_BC_B() - block.p_BV_B(c.contact.first));  // (12)
      const double margin = 1e-9 * w_minus.norm() * 0.2;  // well outside the library's tolerance band
      const double lift = v_plus.z() - v_minus.z();
      if (lift > margin) { EXPECT_TRUE(c.impulse_lifts); }
      if (lift < -margin) { EXPECT_FALSE(c.impulse_lifts); }
      double lowest = std::numeric_limits<double>::infinity();
      for (int i = 1; i <= 4; ++i) {
        lowest = std::min(lowest, (v_plus + c.w_plus.cross(block.p_BV_B(i) - block.p_BC_B())).z());  // (23)
      }
      if (lowest < -margin) { EXPECT_FALSE(c.no_penetration); }
      if (lowest > -1e-15) { EXPECT_TRUE(c.no_penetration); }
      EXPECT_EQ(c.feasible, c.impulse_lifts && c.no_penetration);
    }
  }
}

TEST(FacetImpact, WithLambdaLatZeroEqualsThePlanarMap6) {
  // docs/design.md §3 erratum: λ_lat = 0 gives (6) with λ = λ_lon, b = b1, θ = Θ_yy (pivot edge V1V2) — and, by the
  // cyclic labelling, b = b2, θ = Θ_xx for the pivot edges V2V3 and V4V1.
  const Block block = Fig11Block();
  for (int b = 1; b <= 4; ++b) {
    const PlanarBlock planar = (b % 2 == 0) ? PlanarBlockAboutY(block) : PlanarBlockAboutX(block);
    for (int k = -30; k <= 30; ++k) {
      const double lon = GridValue(k, 30, 3.0);
      const double omega = 1.7;
      const ImpactOutcome out = FacetImpact(block, b, FallingOmega(block, b, omega), {0.0, lon});
      ASSERT_EQ(out.status, ImpactStatus::kOk) << "b " << b << " λ_lon " << lon;
      const Eigen::Vector3d expected = AvrfChatzis(planar, lon) * FallingOmega(block, b, omega);
      EXPECT_LE((out.w_plus_W - expected).norm(), 1e-13 * omega) << "b " << b << " λ_lon " << lon;
      EXPECT_EQ(out.contact_after, Contact::Edge(b + 1, b + 2));
      EXPECT_LE(std::abs(out.tau), 1e-17);
      EXPECT_EQ(out.contact_before, Contact::Edge(b - 1, b));
    }
  }
}

// Counts the grid points of (λ_lat, λ_lon) ∈ [−3, 3]² (2n+1 values each, exact zero included) where the unified
// map does not give the outcome of docs/design.md §3: λ_lat > 0 → V_{b+2}, λ_lat < 0 → V_{b+1} (one feasible vertex
// each), λ_lat = 0 → edge V_{b+1}V_{b+2} (two). Reports the first failure.
int CountUnifiedMapViolations(const Block& block, int b, int n) {
  int violations = 0;
  for (int i = -n; i <= n; ++i) {
    for (int j = -n; j <= n; ++j) {
      const double lat = GridValue(i, n, 3.0), lon = GridValue(j, n, 3.0);
      const ImpactOutcome out = FacetImpact(block, b, FallingOmega(block, b, 1.0), {lat, lon});
      int feasible = 0;
      for (const FacetCandidate& c : out.candidates) feasible += c.feasible ? 1 : 0;
      const Contact expected = i > 0 ? Contact::Vertex(b + 2) : i < 0 ? Contact::Vertex(b + 1) : Contact::Edge(b + 1, b + 2);
      const bool good = out.status == ImpactStatus::kOk && out.contact_after == expected && feasible == (i == 0 ? 2 : 1) &&
                        out.w_plus_W.z() == 0.0;  // (24)
      if (!good && violations++ == 0) {
        ADD_FAILURE() << "b " << b << " λ_lat " << lat << " λ_lon " << lon << ": status " << ToString(out.status)
                      << ", contact " << out.contact_after.ToString() << ", " << feasible << " feasible";
      }
    }
  }
  return violations;
}

TEST(FacetImpact, UnifiedMapHasExactlyOneFeasibleOutcomeWithTheVertexSideOfDesign) {
  // The vertex is picked by feasibility; the sign rule of docs/design.md §3 is only checked here. Step 0.1 for the
  // Fig. 11 block falling about V1V2, step 0.5 for the other pivot edges and two other blocks (a square base
  // and a deep one) to keep the sanitizer run short.
  EXPECT_EQ(CountUnifiedMapViolations(Fig11Block(), 2, 30), 0);
  for (const Block& block : {Fig11Block(), Block::FromMass(0.05, 0.05, 0.20, 1.0), Block::FromMass(0.04, 0.1, 0.25, 3.0)}) {
    for (int b = 1; b <= 4; ++b) EXPECT_EQ(CountUnifiedMapViolations(block, b, 6), 0) << "b " << b;
  }
}

TEST(FacetImpact, FixedTauGivesInfeasibleAndAmbiguousRegionsForTheBlockOfFig11) {
  // Sect. 4.5, Fig. 11: with a fixed τ some parameters have no feasible vertex and some have two.
  const Block block = Fig11Block();
  for (double tau : {1e-4, -1e-4}) {
    std::map<ImpactStatus, int> count;
    const int n = 20;
    for (int i = -n; i <= n; ++i) {
      for (int j = -n; j <= n; ++j) {
        const ImpactOutcome out =
            FacetImpact(block, 2, FallingOmega(block, 2, 1.0), {GridValue(i, n, 2.0), GridValue(j, n, 2.0), FacetTauRule::kFixed, tau});
        ++count[out.status];
        int feasible = 0;
        for (const FacetCandidate& c : out.candidates) feasible += c.feasible ? 1 : 0;
        switch (out.status) {
          case ImpactStatus::kOk:
            EXPECT_EQ(feasible, 1);
            EXPECT_TRUE(out.contact_after.is_vertex());
            EXPECT_EQ(out.tau, tau);
            break;
          case ImpactStatus::kAmbiguous:
            EXPECT_GE(feasible, 2);
            EXPECT_EQ(out.contact_after, Contact{});
            EXPECT_EQ(out.w_plus_W, Eigen::Vector3d::Zero());
            break;
          case ImpactStatus::kInfeasible: EXPECT_EQ(feasible, 0); break;
          case ImpactStatus::kSingular: ADD_FAILURE() << "no singularity expected on this grid"; break;
        }
        EXPECT_EQ(out.candidates.size(), 4u);
      }
    }
    EXPECT_GT(count[ImpactStatus::kInfeasible], 0) << "τ = " << tau;
    EXPECT_GT(count[ImpactStatus::kAmbiguous], 0) << "τ = " << tau;
    EXPECT_GT(count[ImpactStatus::kOk], 0) << "τ = " << tau;
  }
}

TEST(FacetImpact, NoSpinTauIsZeroOnlyForASquareBaseOrLambdaLatZero) {
  // docs/design.md §3 erratum to Sect. 4.5 ("τ = 0 for a homogeneous cuboid").
  const Block slender = Fig11Block();
  const Block square = Block::FromMass(0.05, 0.05, 0.20, 1.0);
  for (int b = 1; b <= 4; ++b) {
    for (double lat : {-0.8, -0.2, 0.3, 1.0}) {
      for (double lon : {-0.5, 0.4, 1.0}) {
        const Eigen::Vector3d w_s = FallingOmega(slender, b, 1.0);
        const double momentum_scale = slender.inertia_C_B().norm() * w_s.norm();
        EXPECT_GT(std::abs(FacetImpact(slender, b, w_s, {lat, lon}).tau), 1e-6 * momentum_scale)
            << "b " << b << " λ_lat " << lat << " λ_lon " << lon;
        EXPECT_LE(std::abs(FacetImpact(slender, b, w_s, {0.0, lon}).tau), 1e-14 * momentum_scale);
        const Eigen::Vector3d w_q = FallingOmega(square, b, 1.0);
        EXPECT_LE(std::abs(FacetImpact(square, b, w_q, {lat, lon}).tau), 1e-14 * square.inertia_C_B().norm());
      }
    }
  }
}

TEST(FacetImpact, FixedTauZeroStaysAvailableAndMatchesNoSpinOnlyForASquareBase) {
  const Block square = Block::FromMass(0.05, 0.05, 0.20, 1.0);
  const Block slender = Fig11Block();
  const ImpactOutcome q_spin = FacetImpact(square, 2, FallingOmega(square, 2, 1.0), {0.4, 0.7});
  const ImpactOutcome q_fixed = FacetImpact(square, 2, FallingOmega(square, 2, 1.0), {0.4, 0.7, FacetTauRule::kFixed, 0.0});
  ASSERT_EQ(q_fixed.status, ImpactStatus::kOk);
  EXPECT_EQ(q_fixed.contact_after, q_spin.contact_after);
  EXPECT_LE((q_fixed.w_plus_W - q_spin.w_plus_W).norm(), 1e-14);
  // Slender block: with τ = 0 the post-impact ω⁺ spins (u_zᵀω⁺ ≠ 0), unlike (24).
  const ImpactOutcome s_fixed = FacetImpact(slender, 2, FallingOmega(slender, 2, 1.0), {0.4, 0.7, FacetTauRule::kFixed, 0.0});
  ASSERT_EQ(s_fixed.status, ImpactStatus::kOk);
  EXPECT_GT(std::abs(s_fixed.w_plus_W.z()), 1e-6);
  EXPECT_EQ(s_fixed.tau, 0.0);
}

TEST(FacetImpact, IsLinearInOmegaMinusForEveryCandidateWhenTauIsZero) {
  const Block block = Fig11Block();
  const Eigen::Vector3d w1(0.2, 1.0, -0.1), w2(-0.4, 0.3, 0.5);
  for (const FacetTauRule rule : {FacetTauRule::kNoSpin, FacetTauRule::kFixed}) {
    const FacetImpactParameters params{0.35, 0.6, rule, 0.0};
    const ImpactOutcome o1 = FacetImpact(block, 2, w1, params);
    const ImpactOutcome o2 = FacetImpact(block, 2, w2, params);
    const ImpactOutcome o12 = FacetImpact(block, 2, 2.0 * w1 - 3.0 * w2, params);
    for (int i = 0; i < 4; ++i) {
      const Eigen::Vector3d expected = 2.0 * o1.candidates[i].w_plus - 3.0 * o2.candidates[i].w_plus;
      EXPECT_LE((o12.candidates[i].w_plus - expected).norm(), kVectorRelTol * expected.norm()) << "candidate " << i;
      const double tau_expected = 2.0 * o1.candidates[i].tau - 3.0 * o2.candidates[i].tau;
      EXPECT_NEAR(o12.candidates[i].tau, tau_expected, kVectorRelTol * std::abs(tau_expected) + 1e-18);
    }
    // Scaling ω⁻ by k > 0 keeps the feasible vertex and scales ω⁺.
    const Eigen::Vector3d falling = FallingOmega(block, 2, 1.0);
    const ImpactOutcome base = FacetImpact(block, 2, falling, params);
    const ImpactOutcome scaled = FacetImpact(block, 2, 3.5 * falling, params);
    EXPECT_EQ(scaled.status, base.status);
    EXPECT_EQ(scaled.contact_after, base.contact_after);
    EXPECT_LE((scaled.w_plus_W - 3.5 * base.w_plus_W).norm(), kVectorRelTol * scaled.w_plus_W.norm());
  }
}

TEST(FacetImpact, MirrorSymmetryYToMinusYFlipsLambdaLat) {
  // Pivot edge V1V2 (b = 2) maps onto itself; V3 ↔ V4; ω and τ are axial; λ_lat → −λ_lat.
  const Block block = Fig11Block();
  const Eigen::Vector3d w_minus = FallingOmega(block, 2, 1.2);
  ASSERT_EQ(testing::MirrorAxial(w_minus), w_minus);
  for (double lat : {-1.5, -0.4, 0.0, 0.25, 0.9}) {
    for (double lon : {-0.5, 0.5, 1.0}) {
      for (const FacetTauRule rule : {FacetTauRule::kNoSpin, FacetTauRule::kFixed}) {
        const double tau = rule == FacetTauRule::kFixed ? 2e-5 : 0.0;
        const ImpactOutcome out = FacetImpact(block, 2, w_minus, {lat, lon, rule, tau});
        const ImpactOutcome mir = FacetImpact(block, 2, w_minus, {-lat, lon, rule, -tau});
        ASSERT_EQ(mir.status, out.status) << "λ_lat " << lat << " λ_lon " << lon;
        EXPECT_LE((mir.w_plus_W - testing::MirrorAxial(out.w_plus_W)).norm(), kVectorRelTol * w_minus.norm());
        EXPECT_NEAR(mir.tau, -out.tau, 1e-18);
        if (out.contact_after.is_vertex()) {
          EXPECT_EQ(mir.contact_after, Contact::Vertex(testing::MirrorVertex(out.contact_after.first)));
        } else {
          EXPECT_EQ(mir.contact_after, out.contact_after);  // V3V4 and "none" are their own mirror images
        }
        for (int a = 1; a <= 4; ++a) {
          EXPECT_EQ(mir.candidates[testing::MirrorVertex(a) - 1].feasible, out.candidates[a - 1].feasible);
        }
      }
    }
  }
}

TEST(FacetImpact, EnergyIsTheKineticEnergyAboutPivotAndNewSupport) {
  const Block block = Fig11Block();
  const Eigen::Vector3d w_minus = FallingOmega(block, 2, 1.0);
  for (double lat : {-0.5, 0.0, 0.5}) {
    for (double lon : {0.0, 0.5, 1.0, -0.5}) {
      const ImpactOutcome out = FacetImpact(block, 2, w_minus, {lat, lon});
      ASSERT_EQ(out.status, ImpactStatus::kOk);
      const int a = out.contact_after.first;
      const ImpactGeometry g = GeometryOf(block, 2, a, lat, lon);
      const double before = testing::KineticEnergyFromComVelocity(g, g.p_b, w_minus);
      const double after = testing::KineticEnergyFromComVelocity(g, g.p_a, out.w_plus_W);
      EXPECT_NEAR(out.energy_before_J, before, 1e-14 * before);
      EXPECT_NEAR(out.delta_energy_J, after - before, 1e-13 * before);
      EXPECT_EQ(out.energy_nonincreasing, out.delta_energy_J <= 0.0 || out.delta_energy_J <= 1e-12 * before);
      EXPECT_EQ(out.within_geometric_bounds, WithinFacetBounds(lat, lon));
    }
  }
  // λ_lat = 0, λ_lon = 0: r = 1 in (6), elastic.
  const ImpactOutcome elastic = FacetImpact(block, 2, w_minus, {0.0, 0.0});
  EXPECT_LE(std::abs(elastic.delta_energy_J), 1e-14 * elastic.energy_before_J);
  EXPECT_TRUE(elastic.energy_nonincreasing);
  EXPECT_FALSE(FacetImpact(block, 2, w_minus, {0.0, -0.5}).energy_nonincreasing);  // r > 1
}

TEST(FacetImpact, FallingDirectionOfFig11IsPositiveY) {
  // In rockfit's frame ω⁻ = (0, −1, 0) about V1V2 raises V3 and V4: it is no impact, and no candidate is
  // feasible. The block falls onto its base with ω⁻ = (0, +1, 0) (docs/design.md §2: w_B ≈ (0, +ω, 0)).
  const Block block = Fig11Block();
  const Eigen::Vector3d lifting(0.0, -1.0, 0.0);
  EXPECT_GT(lifting.cross(block.p_BV_B(3) - block.p_BV_B(2)).z(), 0.0);
  EXPECT_EQ(FacetImpact(block, 2, lifting, {0.3, 0.8}).status, ImpactStatus::kInfeasible);
  EXPECT_EQ(FacetImpact(block, 2, Eigen::Vector3d(0.0, 1.0, 0.0), {0.3, 0.8}).status, ImpactStatus::kOk);
}

TEST(FacetImpact, AvrfZeroBringsTheBlockToRest) {
  // (6) gives r = 0 at λ = (θ + mh²)/(m b²): ω⁺ = 0 for every candidate, the whole base stays down.
  const Block block = Fig11Block();
  const PlanarBlock p = PlanarBlockAboutY(block);
  const double lon_rest = LambdaFromAvrf(p, 0.0);
  const ImpactOutcome out = FacetImpact(block, 2, FallingOmega(block, 2, 1.0), {0.0, lon_rest});
  EXPECT_EQ(out.status, ImpactStatus::kOk);
  EXPECT_EQ(out.contact_after, Contact{});
  EXPECT_LE(out.w_plus_W.norm(), 1e-14);
  EXPECT_NEAR(out.delta_energy_J, -out.energy_before_J, 1e-14 * out.energy_before_J);
}

TEST(FacetImpact, SingularMapIsAStatusNotNaN) {
  // (6) is singular at λ = −(θ + mh²)/(m b²); with λ_lat = 0 so is the facet map for V3 and V4.
  const Block block = Fig11Block();
  const PlanarBlock p = PlanarBlockAboutY(block);
  const double lon_singular = -(p.theta_kg_m2 + p.mass_kg * p.h_m * p.h_m) / (p.mass_kg * p.b_m * p.b_m);
  for (const FacetTauRule rule : {FacetTauRule::kNoSpin, FacetTauRule::kFixed}) {
    const ImpactOutcome out = FacetImpact(block, 2, FallingOmega(block, 2, 1.0), {0.0, lon_singular, rule, 0.0});
    EXPECT_EQ(out.status, ImpactStatus::kSingular) << ToString(rule);
    EXPECT_EQ(out.candidates[2].status, ImpactStatus::kSingular);
    EXPECT_EQ(out.candidates[3].status, ImpactStatus::kSingular);
    EXPECT_TRUE(out.w_plus_W.allFinite());
    for (const FacetCandidate& c : out.candidates) EXPECT_TRUE(c.w_plus.allFinite());
    EXPECT_TRUE(std::isfinite(out.delta_energy_J));
  }
}

TEST(FacetImpact, PrecomputedNoSpinOperatorsGiveTheSameOutcome) {
  const Block block = Fig11Block();
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> lambda(-3.0, 3.0);
  std::uniform_real_distribution<double> component(-1.0, 1.0);
  int decided = 0;
  for (int trial = 0; trial < 200; ++trial) {
    FacetImpactParameters params;
    params.lambda_lat = lambda(rng);
    params.lambda_lon = lambda(rng);
    const int b = 1 + trial % 4;
    const FacetNoSpinOperators operators = MakeFacetNoSpinOperators(block, b, params);
    const Eigen::Vector3d w_minus(component(rng), component(rng), component(rng));
    const ImpactOutcome direct = FacetImpact(block, b, w_minus, params);
    const ImpactOutcome cached = FacetImpact(block, operators, w_minus, params);
    ASSERT_EQ(direct.status, cached.status) << trial;
    ASSERT_EQ(direct.candidates.size(), cached.candidates.size()) << trial;
    for (std::size_t a = 0; a < direct.candidates.size(); ++a) {
      EXPECT_EQ(direct.candidates[a].status, cached.candidates[a].status) << trial;
      EXPECT_EQ(direct.candidates[a].feasible, cached.candidates[a].feasible) << trial;
      EXPECT_NEAR((direct.candidates[a].w_plus - cached.candidates[a].w_plus).norm(), 0.0, 1e-12) << trial;
    }
    if (direct.status != ImpactStatus::kOk) continue;
    ++decided;
    EXPECT_EQ(direct.contact_after, cached.contact_after) << trial;
    EXPECT_NEAR((direct.w_plus_B - cached.w_plus_B).norm(), 0.0, 1e-12) << trial;
    EXPECT_NEAR(direct.tau, cached.tau, 1e-12) << trial;
  }
  EXPECT_GT(decided, 20);
  FacetImpactParameters fixed;
  fixed.tau_rule = FacetTauRule::kFixed;
  EXPECT_THROW(MakeFacetNoSpinOperators(block, 2, fixed), InvalidArgument);
}

// The outcome of a direction scaled by r is the full map's for r times that direction: the same decision, ω⁺ and
// τ times r, energies times r² (random λ's, directions, pivots and scales over eight decades).
TEST(FacetImpact, ScaledNoSpinOutcomeOfADirectionIsTheOutcomeOfTheScaledRate) {
  const Block block = Fig11Block();
  std::mt19937 rng(131);
  std::uniform_real_distribution<double> lambda(-3.0, 3.0);
  std::uniform_real_distribution<double> component(-1.0, 1.0);
  std::uniform_real_distribution<double> log10_scale(-4.0, 4.0);
  int decided = 0;
  for (int trial = 0; trial < 200; ++trial) {
    FacetImpactParameters params;
    params.lambda_lat = trial % 3 == 0 ? 0.0 : lambda(rng);  // a third planar (edge contact after)
    params.lambda_lon = lambda(rng);
    const int b = 1 + trial % 4;
    const Eigen::Vector3d e =
        trial % 2 == 0 ? FallingOmega(block, b, 1.0) : Eigen::Vector3d(component(rng), component(rng), component(rng));
    const double r = std::pow(10.0, log10_scale(rng));
    const ImpactOutcome unit = FacetImpact(block, b, e, params);
    const ImpactOutcome scaled = ScaledFacetOutcome(unit, r);
    const ImpactOutcome direct = FacetImpact(block, b, r * e, params);
    ASSERT_EQ(direct.status, scaled.status) << trial;
    EXPECT_EQ(direct.contact_before, scaled.contact_before) << trial;
    EXPECT_NEAR(direct.energy_before_J, scaled.energy_before_J, 1e-12 * direct.energy_before_J) << trial;
    if (direct.status != ImpactStatus::kOk) continue;
    ++decided;
    EXPECT_EQ(direct.contact_after, scaled.contact_after) << trial;
    const double w_scale = r * e.norm();
    EXPECT_NEAR((direct.w_plus_B - scaled.w_plus_B).norm(), 0.0, kVectorRelTol * w_scale) << trial;
    EXPECT_NEAR((direct.w_plus_W - scaled.w_plus_W).norm(), 0.0, kVectorRelTol * w_scale) << trial;
    EXPECT_NEAR(direct.tau, scaled.tau, kVectorRelTol * w_scale * block.mass()) << trial;
    EXPECT_NEAR(direct.delta_energy_J, scaled.delta_energy_J, 1e-12 * direct.energy_before_J) << trial;
    EXPECT_EQ(direct.energy_nonincreasing, scaled.energy_nonincreasing) << trial;
  }
  EXPECT_GT(decided, 40);
  const ImpactOutcome unit = FacetImpact(block, 2, FallingOmega(block, 2, 1.0), {});
  EXPECT_THROW(ScaledFacetOutcome(unit, 0.0), InvalidArgument);
  EXPECT_THROW(ScaledFacetOutcome(unit, -1.0), InvalidArgument);
  EXPECT_THROW(ScaledFacetOutcome(unit, std::numeric_limits<double>::quiet_NaN()), InvalidArgument);
}

TEST(FacetImpact, GeometricBound27) {
  EXPECT_TRUE(WithinFacetBounds(1.0, -1.0));
  EXPECT_FALSE(WithinFacetBounds(1.01, 0.0));
  EXPECT_FALSE(WithinFacetBounds(0.0, -1.01));
}

TEST(FacetImpact, NamesAndBadArguments) {
  EXPECT_STREQ(ToString(FacetTauRule::kNoSpin), "no-spin");
  EXPECT_STREQ(ToString(FacetTauRule::kFixed), "fixed");
  const Block block = Fig11Block();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(FacetImpact(block, 2, Eigen::Vector3d(0, nan, 0), {}), InvalidArgument);
  EXPECT_THROW(FacetImpact(block, 2, Eigen::Vector3d(0, 1, 0), {nan, 0.0}), InvalidArgument);
  EXPECT_THROW(FacetImpact(block, 2, Eigen::Vector3d(0, 1, 0), {0.0, std::numeric_limits<double>::infinity()}),
               InvalidArgument);
  EXPECT_THROW(FacetImpact(block, 2, Eigen::Vector3d(0, 1, 0), {0.0, 1.0, FacetTauRule::kFixed, nan}), InvalidArgument);
}

}  // namespace
}  // namespace rockfit::core
