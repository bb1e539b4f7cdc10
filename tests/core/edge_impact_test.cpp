#include "rockfit/core/edge_impact.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "impact_equations.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/core/facet_impact.hpp"

namespace rockfit::core {
namespace {

constexpr double kBalanceRelTol = 1e-12;   // (17) residual, the acceptance level of docs/design.md §12
constexpr double kVectorRelTol = 1e-12;    // two evaluations of the same linear map

// Tilt 0 (flat base), 1e-8 (nearly flat) and a generic tilt [rad].
const double kTilts[] = {0.0, 1e-8, 0.2};
// Every ordered pair (pivot V_b, landing V_a) of neighbouring base vertices.
const std::pair<int, int> kEdges[] = {{1, 2}, {2, 1}, {2, 3}, {3, 2}, {3, 4}, {4, 3}, {4, 1}, {1, 4}};

Block Fig11Block() { return Block::FromMass(0.05, 0.03, 0.20, 1.0); }

// The impact geometry in W, rebuilt here from the block and the attitude (not taken from the library).
ImpactGeometry GeometryOf(const Block& block, const Eigen::Matrix3d& R_WB, int pivot, int landing, double lambda) {
  ImpactGeometry g;
  g.mass_kg = block.mass();
  g.inertia_C = R_WB * block.inertia_C_B() * R_WB.transpose();
  g.p_C = R_WB * block.p_BC_B();
  g.p_b = R_WB * block.p_BV_B(pivot);
  g.p_a = R_WB * block.p_BV_B(landing);
  g.p_R = 0.5 * (g.p_a + g.p_b) + 0.5 * lambda * (g.p_a - g.p_b);  // (19)
  return g;
}

Eigen::Vector3d RandomOmega(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  return {u(rng), u(rng), u(rng)};
}

// A pre-impact ω⁻ of vertex rocking about V_b that brings V_a down: ω⁻ = ω_n n + ω_s e_z + ω_e e with
// the horizontal axis n ⟂ edge chosen so that V_a descends.
Eigen::Vector3d FallingOmega(const Block& block, const Eigen::Matrix3d& R_WB, int pivot, int landing, double spin,
                             double along_edge) {
  const Eigen::Vector3d e = (R_WB * (block.p_BV_B(landing) - block.p_BV_B(pivot))).normalized();
  Eigen::Vector3d n = e.cross(Eigen::Vector3d::UnitZ()).normalized();
  if (n.cross(e).z() > 0.0) n = -n;  // (ω × e)_z < 0: V_a moves down
  return n + spin * Eigen::Vector3d::UnitZ() + along_edge * e;
}

TEST(EdgeImpactAttitude, LiftsTheRestOfTheBaseByTheTiltAboutTheEdge) {
  const Block block = Fig11Block();
  for (const auto& [pivot, landing] : kEdges) {
    for (double tilt : kTilts) {
      const Eigen::Matrix3d R = EdgeImpactAttitude(block, pivot, landing, tilt);
      EXPECT_LE((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 1e-15);
      const Eigen::Vector3d p_b = R * block.p_BV_B(pivot), p_a = R * block.p_BV_B(landing);
      EXPECT_NEAR(p_a.z(), p_b.z(), 1e-17);
      // The edge keeps its body direction.
      EXPECT_LE((p_a - p_b - (block.p_BV_B(landing) - block.p_BV_B(pivot))).norm(), 1e-17);
      // The two other vertices rise by (their distance from the edge line)·sin(tilt).
      const Eigen::Vector3d e = (block.p_BV_B(landing) - block.p_BV_B(pivot)).normalized();
      for (int k = 1; k <= 4; ++k) {
        if (k == pivot || k == landing) continue;
        const Eigen::Vector3d d = block.p_BV_B(k) - block.p_BV_B(pivot);
        const double distance = (d - d.dot(e) * e).norm();
        EXPECT_NEAR((R * block.p_BV_B(k)).z() - p_b.z(), distance * std::sin(tilt), 1e-16) << "V" << k;
      }
    }
  }
}

TEST(EdgeImpactAttitude, OnEdgeV1V2ItIsTheReleaseAttitudeOfDesign) {
  // docs/design.md §2: resting on V1V2 with the +x side lifted by α is φy = −α, R_WB = R_y(−α).
  const Block block = Fig11Block();
  const double alpha = 0.2;
  const Eigen::Matrix3d expected = Eigen::AngleAxisd(-alpha, Eigen::Vector3d::UnitY()).toRotationMatrix();
  EXPECT_LE((EdgeImpactAttitude(block, 1, 2, alpha) - expected).norm(), 1e-16);
  EXPECT_LE((EdgeImpactAttitude(block, 2, 1, alpha) - expected).norm(), 1e-16);
  EXPECT_EQ(EdgeImpactAttitude(block, 1, 2, 0.0), Eigen::Matrix3d::Identity());
}

TEST(EdgeImpactAttitude, RejectsNonNeighboursAndTiltsOutsideZeroToQuarterTurn) {
  const Block block = Fig11Block();
  EXPECT_THROW(EdgeImpactAttitude(block, 1, 3, 0.1), InvalidArgument);
  EXPECT_THROW(EdgeImpactAttitude(block, 1, 2, -0.1), InvalidArgument);
  EXPECT_THROW(EdgeImpactAttitude(block, 1, 2, 2.0), InvalidArgument);
  EXPECT_THROW(EdgeImpactAttitude(block, 1, 2, std::numeric_limits<double>::quiet_NaN()), InvalidArgument);
}

TEST(EdgeImpact, SatisfiesImpulseMomentumBalance17AndKinematics12AtEveryTilt) {
  const Block block = Fig11Block();
  std::mt19937 rng(2021);
  for (double tilt : kTilts) {
    for (const auto& [pivot, landing] : kEdges) {
      const Eigen::Matrix3d R = EdgeImpactAttitude(block, pivot, landing, tilt);
      for (double lambda : {-1.0, -0.3, 0.0, 0.5, 1.0, 1.7}) {
        for (double tau : {0.0, 2e-3, -1e-4}) {
          const Eigen::Vector3d w_minus = RandomOmega(rng);
          const ImpactOutcome out = EdgeImpact(block, R, pivot, landing, w_minus, {lambda, tau});
          ASSERT_EQ(out.status, ImpactStatus::kOk);
          const ImpactGeometry g = GeometryOf(block, R, pivot, landing, lambda);
          EXPECT_LE(testing::MomentumBalanceRelResidual(g, w_minus, out.w_plus_W, tau), kBalanceRelTol)
              << "tilt " << tilt << " V" << pivot << "→V" << landing << " λ " << lambda << " τ " << tau;
          // (12): after the impact V_a is at rest; the body-frame ω⁺ is the same vector.
          EXPECT_LE((out.w_plus_B - R.transpose() * out.w_plus_W).norm(), 1e-15 * out.w_plus_W.norm());
          EXPECT_EQ(out.tau, tau);
          EXPECT_EQ(out.contact_before, Contact::Vertex(pivot));
          EXPECT_EQ(out.w_minus_W, w_minus);
          EXPECT_TRUE(out.candidates.empty());
        }
      }
    }
  }
}

TEST(EdgeImpact, IsLinearInOmegaMinusWhenTauIsZero) {
  const Block block = Fig11Block();
  std::mt19937 rng(5);
  for (double tilt : kTilts) {
    const Eigen::Matrix3d R = EdgeImpactAttitude(block, 3, 4, tilt);
    const Eigen::Vector3d w1 = RandomOmega(rng), w2 = RandomOmega(rng);
    const EdgeImpactParameters params{0.6, 0.0};
    const Eigen::Vector3d p1 = EdgeImpact(block, R, 3, 4, w1, params).w_plus_W;
    const Eigen::Vector3d p2 = EdgeImpact(block, R, 3, 4, w2, params).w_plus_W;
    const Eigen::Vector3d p12 = EdgeImpact(block, R, 3, 4, 1.5 * w1 - 2.0 * w2, params).w_plus_W;
    const Eigen::Vector3d expected = 1.5 * p1 - 2.0 * p2;
    EXPECT_LE((p12 - expected).norm(), kVectorRelTol * expected.norm()) << "tilt " << tilt;
  }
}

TEST(EdgeImpact, WithTauZeroEnergyIsConservedAtLambdaZeroAndLostExactlyForPositiveLambda) {
  // Sect. 4.8: "for τ = 0, (26) implies λ ≥ 0"; at λ = 0 the impact is elastic.
  const Block block = Fig11Block();
  std::mt19937 rng(26);
  for (double tilt : kTilts) {
    for (const auto& [pivot, landing] : kEdges) {
      const Eigen::Matrix3d R = EdgeImpactAttitude(block, pivot, landing, tilt);
      const Eigen::Vector3d w_minus = RandomOmega(rng);
      const ImpactOutcome elastic = EdgeImpact(block, R, pivot, landing, w_minus, {0.0, 0.0});
      ASSERT_EQ(elastic.status, ImpactStatus::kOk);
      EXPECT_LE(std::abs(elastic.delta_energy_J), 1e-13 * elastic.energy_before_J);
      EXPECT_TRUE(elastic.energy_nonincreasing);
      for (double lambda : {1e-3, 0.1, 0.5, 1.0, 1.5}) {
        const ImpactOutcome out = EdgeImpact(block, R, pivot, landing, w_minus, {lambda, 0.0});
        EXPECT_LT(out.delta_energy_J, 0.0) << "tilt " << tilt << " λ " << lambda;
        EXPECT_TRUE(out.energy_nonincreasing);
      }
      for (double lambda : {-1e-3, -0.5, -1.0}) {
        const ImpactOutcome out = EdgeImpact(block, R, pivot, landing, w_minus, {lambda, 0.0});
        EXPECT_GT(out.delta_energy_J, 0.0) << "tilt " << tilt << " λ " << lambda;
        EXPECT_FALSE(out.energy_nonincreasing);
      }
    }
  }
}

TEST(EdgeImpact, EnergiesAreTheKineticEnergiesAboutPivotAndLandingVertex) {
  const Block block = Fig11Block();
  std::mt19937 rng(3);
  for (double tilt : kTilts) {
    const Eigen::Matrix3d R = EdgeImpactAttitude(block, 4, 1, tilt);
    const Eigen::Vector3d w_minus = RandomOmega(rng);
    const ImpactOutcome out = EdgeImpact(block, R, 4, 1, w_minus, {0.8, 1e-3});
    const ImpactGeometry g = GeometryOf(block, R, 4, 1, 0.8);
    const double before = testing::KineticEnergyFromComVelocity(g, g.p_b, w_minus);
    const double after = testing::KineticEnergyFromComVelocity(g, g.p_a, out.w_plus_W);
    EXPECT_NEAR(out.energy_before_J, before, 1e-14 * before);
    EXPECT_NEAR(out.energy_after_J, after, 1e-14 * after);
    EXPECT_NEAR(out.delta_energy_J, after - before, 1e-14 * before);
  }
}

TEST(EdgeImpact, MirrorSymmetryYToMinusY) {
  // Mirroring the world y → −y maps the block onto itself with V1 ↔ V2, V3 ↔ V4; ω and τ u_z are axial.
  const Block block = Fig11Block();
  const Eigen::Matrix3d M = Eigen::Vector3d(1.0, -1.0, 1.0).asDiagonal();
  std::mt19937 rng(99);
  for (double tilt : kTilts) {
    for (const auto& [pivot, landing] : kEdges) {
      const int pivot_m = testing::MirrorVertex(pivot), landing_m = testing::MirrorVertex(landing);
      const Eigen::Matrix3d R = EdgeImpactAttitude(block, pivot, landing, tilt);
      const Eigen::Matrix3d R_m = EdgeImpactAttitude(block, pivot_m, landing_m, tilt);
      EXPECT_LE((R_m - M * R * M).norm(), 1e-15);
      const Eigen::Vector3d w_minus = FallingOmega(block, R, pivot, landing, 0.3, 0.2);
      const ImpactOutcome out = EdgeImpact(block, R, pivot, landing, w_minus, {0.7, 1e-3});
      const ImpactOutcome mirrored =
          EdgeImpact(block, R_m, pivot_m, landing_m, testing::MirrorAxial(w_minus), {0.7, -1e-3});
      ASSERT_EQ(mirrored.status, ImpactStatus::kOk);
      EXPECT_LE((mirrored.w_plus_W - testing::MirrorAxial(out.w_plus_W)).norm(), kVectorRelTol * out.w_plus_W.norm());
      EXPECT_NEAR(mirrored.delta_energy_J, out.delta_energy_J, 1e-13 * out.energy_before_J);
      const Contact expected_after =
          out.contact_after.is_vertex() ? Contact::Vertex(landing_m) : Contact::Edge(pivot_m, landing_m);
      EXPECT_EQ(mirrored.contact_after, expected_after);
    }
  }
}

TEST(EdgeImpact, ContactAfterFollowsTheVerticalVelocityOfThePivot) {
  const Block block = Fig11Block();
  int lifts = 0, stays = 0;
  for (double tilt : kTilts) {
    for (const auto& [pivot, landing] : kEdges) {
      const Eigen::Matrix3d R = EdgeImpactAttitude(block, pivot, landing, tilt);
      // Within (25) a falling block always lifts V_b; a λ beyond the planar AVRF-zero value of the edge
      // (θ + mh²)/(m b²) ≈ 22 (edges along x) or ≈ 60 (along y) reverses the rocking and presses V_b down.
      for (double lambda : {0.0, 0.5, 1.0, 40.0, 80.0}) {
        for (double spin : {-0.5, 0.0, 0.5}) {
          const Eigen::Vector3d w_minus = FallingOmega(block, R, pivot, landing, spin, 0.1);
          const ImpactOutcome out = EdgeImpact(block, R, pivot, landing, w_minus, {lambda, 0.0});
          const ImpactGeometry g = GeometryOf(block, R, pivot, landing, lambda);
          // Velocity of V_b while rotating with ω⁺ about V_a.
          const double v_b_up = out.w_plus_W.cross(g.p_b - g.p_a).z();
          if (v_b_up > 1e-9 * out.w_plus_W.norm()) {
            EXPECT_EQ(out.contact_after, Contact::Vertex(landing));
            ++lifts;
          } else if (v_b_up < -1e-9 * out.w_plus_W.norm()) {
            EXPECT_EQ(out.contact_after, Contact::Edge(pivot, landing));
            ++stays;
          }
        }
      }
    }
  }
  EXPECT_GT(lifts, 0);  // both branches are exercised
  EXPECT_GT(stays, 0);
}

TEST(EdgeImpact, RotationAboutTheImpactingEdgeIsUnchangedAndKeepsEdgeContact) {
  // ω⁻ along V_bV_a: the edge is already at rest, R_a ω⁻ = R_b ω⁻, so (18) gives ω⁺ = ω⁻ for every λ (τ = 0).
  const Block block = Fig11Block();
  for (double tilt : kTilts) {
    for (const auto& [pivot, landing] : kEdges) {
      const Eigen::Matrix3d R = EdgeImpactAttitude(block, pivot, landing, tilt);
      const Eigen::Vector3d w_minus = 1.3 * (R * (block.p_BV_B(landing) - block.p_BV_B(pivot))).normalized();
      for (double lambda : {-0.5, 0.0, 1.0}) {
        const ImpactOutcome out = EdgeImpact(block, R, pivot, landing, w_minus, {lambda, 0.0});
        EXPECT_LE((out.w_plus_W - w_minus).norm(), 1e-14);
        EXPECT_EQ(out.contact_after, Contact::Edge(pivot, landing));
        EXPECT_LE(std::abs(out.delta_energy_J), 1e-14 * out.energy_before_J);
      }
    }
  }
}

TEST(EdgeImpact, FlatLandingEqualsTheFacetCandidateWithTheResultantOnThatEdge) {
  // At tilt 0 a block rocking about V1V2 (ω⁻ = (0, ω, 0)) lands flat. Seen as an edge impact on V2V3 with
  // pivot V2, R = (λ b1, b2, 0) (19) is the point (21) with λ_lat = 1, λ_lon = λ, and V_a = V3: both
  // parameterisations must give the same ω⁺ for the same τ.
  const Block block = Fig11Block();
  const Eigen::Vector3d w_minus(0.0, 1.3, 0.0);
  for (double lambda : {-0.5, 0.0, 0.4, 1.0}) {
    for (double tau : {0.0, 1e-4}) {
      const ImpactOutcome edge = EdgeImpact(block, EdgeImpactAttitude(block, 2, 3, 0.0), 2, 3, w_minus, {lambda, tau});
      const ImpactOutcome facet = FacetImpact(block, 2, w_minus, {1.0, lambda, FacetTauRule::kFixed, tau});
      EXPECT_LE((edge.w_plus_W - facet.candidates[2].w_plus).norm(), kVectorRelTol * w_minus.norm())
          << "λ " << lambda << " τ " << tau;
    }
  }
}

TEST(EdgeImpact, SingularLambdasAreRootsOfTheDeterminantAndGiveASingularStatus) {
  const Block block = Fig11Block();
  for (double tilt : kTilts) {
    for (const auto& [pivot, landing] : kEdges) {
      const Eigen::Matrix3d R = EdgeImpactAttitude(block, pivot, landing, tilt);
      const std::vector<double> roots = EdgeImpactSingularLambdas(block, R, pivot, landing);
      ASSERT_FALSE(roots.empty()) << "V" << pivot << "→V" << landing;
      for (double lambda : roots) {
        EXPECT_FALSE(WithinEdgeBounds(lambda));  // slender block: singularities lie beyond (25)
        // det(Θ − m R_R R_a) at the root, relative to the product of the column norms (Hadamard bound).
        const ImpactGeometry g = GeometryOf(block, R, pivot, landing, lambda);
        const Eigen::Matrix3d m = g.inertia_C - g.mass_kg * SkewOf(g.p_R, g.p_C) * SkewOf(g.p_a, g.p_C);
        const double hadamard = m.col(0).norm() * m.col(1).norm() * m.col(2).norm();
        EXPECT_LE(std::abs(m.determinant()), 1e-13 * hadamard) << "λ = " << lambda;
        const ImpactOutcome out = EdgeImpact(block, R, pivot, landing, Eigen::Vector3d(0.3, -1.0, 0.2), {lambda, 0.0});
        EXPECT_EQ(out.status, ImpactStatus::kSingular) << "λ = " << lambda;
        EXPECT_TRUE(out.w_plus_W.allFinite());
        EXPECT_TRUE(std::isfinite(out.delta_energy_J));
        EXPECT_FALSE(out.energy_nonincreasing);
        EXPECT_EQ(out.contact_after, Contact{});
        // Away from the root the map is regular again.
        EXPECT_EQ(EdgeImpact(block, R, pivot, landing, Eigen::Vector3d(0.3, -1.0, 0.2), {lambda + 1e-3, 0.0}).status,
                  ImpactStatus::kOk);
      }
      // The determinant is invariant under rotations: the roots do not depend on the tilt.
      const std::vector<double> flat = EdgeImpactSingularLambdas(block, Eigen::Matrix3d::Identity(), pivot, landing);
      ASSERT_EQ(flat.size(), roots.size());
      for (std::size_t i = 0; i < roots.size(); ++i) EXPECT_NEAR(flat[i], roots[i], 1e-9 * std::abs(roots[i]));
    }
  }
}

TEST(EdgeImpactOperators, SatisfyBalance17AndGiveTheOutcomeOfTheMapInWAtRandomAttitudes) {
  const Block block = Fig11Block();
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const auto& [pivot, landing] : kEdges) {
    for (double lambda : {-1.0, 0.0, 0.45, 1.0, 1.7}) {
      for (double tau : {0.0, 2e-3, -1e-4}) {
        const EdgeImpactOperators operators = MakeEdgeImpactOperators(block, pivot, landing, {lambda, tau});
        ASSERT_TRUE(operators.solvable);
        for (int trial = 0; trial < 4; ++trial) {
          // Any attitude: the operators' map is (18) turned into B, whatever R_WB.
          const Eigen::Matrix3d R = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
          const Eigen::Vector3d w_minus_W = RandomOmega(rng);
          const Eigen::Vector3d w_minus_B = R.transpose() * w_minus_W;
          const ImpactOutcome out = EdgeImpact(operators, R, w_minus_B);
          ASSERT_EQ(out.status, ImpactStatus::kOk);
          const ImpactGeometry g = GeometryOf(block, R, pivot, landing, lambda);
          EXPECT_LE(testing::MomentumBalanceRelResidual(g, out.w_minus_W, out.w_plus_W, tau), kBalanceRelTol)
              << "V" << pivot << "→V" << landing << " λ " << lambda << " τ " << tau;
          EXPECT_LE((out.w_plus_W - R * out.w_plus_B).norm(), 1e-15 * out.w_plus_W.norm());
          const ImpactOutcome in_W = EdgeImpact(block, R, pivot, landing, out.w_minus_W, {lambda, tau});
          EXPECT_LE((out.w_plus_W - in_W.w_plus_W).norm(), kVectorRelTol * in_W.w_plus_W.norm());
          EXPECT_NEAR(out.energy_before_J, in_W.energy_before_J, kVectorRelTol * in_W.energy_before_J);
          EXPECT_NEAR(out.energy_after_J, in_W.energy_after_J, kVectorRelTol * in_W.energy_after_J);
          EXPECT_EQ(out.contact_after, in_W.contact_after);
          EXPECT_EQ(out.contact_before, Contact::Vertex(pivot));
          EXPECT_EQ(out.tau, tau);
          EXPECT_EQ(out.within_geometric_bounds, WithinEdgeBounds(lambda));
        }
      }
    }
  }
}

TEST(EdgeImpactOperators, AreSingularAtTheSingularLambdasAndRejectBadArguments) {
  const Block block = Fig11Block();
  for (const auto& [pivot, landing] : kEdges) {
    for (double lambda : EdgeImpactSingularLambdas(block, Eigen::Matrix3d::Identity(), pivot, landing)) {
      const EdgeImpactOperators operators = MakeEdgeImpactOperators(block, pivot, landing, {lambda, 0.0});
      EXPECT_FALSE(operators.solvable) << "λ = " << lambda;
      const Eigen::Matrix3d R = EdgeImpactAttitude(block, pivot, landing, 0.2);
      const ImpactOutcome out = EdgeImpact(operators, R, Eigen::Vector3d(0.3, -1.0, 0.2));
      EXPECT_EQ(out.status, ImpactStatus::kSingular);
      EXPECT_EQ(out.contact_after, Contact{});
      EXPECT_FALSE(out.energy_nonincreasing);
      EXPECT_TRUE(MakeEdgeImpactOperators(block, pivot, landing, {lambda + 1e-3, 0.0}).solvable);
    }
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(MakeEdgeImpactOperators(block, 1, 3, {}), InvalidArgument);
  EXPECT_THROW(MakeEdgeImpactOperators(block, 1, 2, {nan, 0.0}), InvalidArgument);
  EXPECT_THROW(MakeEdgeImpactOperators(block, 1, 2, {1.0, nan}), InvalidArgument);
  const EdgeImpactOperators operators = MakeEdgeImpactOperators(block, 1, 2, {});
  EXPECT_THROW(EdgeImpact(operators, Eigen::Matrix3d::Identity(), Eigen::Vector3d(nan, 0, 0)), InvalidArgument);
}

TEST(EdgeImpact, SquareBaseHasSingularitiesBeyondTheBoundsToo) {
  const Block block = Block::FromMass(0.05, 0.05, 0.20, 1.0);  // the block of Fig. 9
  const std::vector<double> roots = EdgeImpactSingularLambdas(block, EdgeImpactAttitude(block, 1, 4, 0.0873), 1, 4);
  ASSERT_FALSE(roots.empty());
  for (double lambda : roots) EXPECT_LT(lambda, -1.0);
}

TEST(EdgeImpact, GeometricBound25) {
  EXPECT_TRUE(WithinEdgeBounds(-1.0));
  EXPECT_TRUE(WithinEdgeBounds(1.0));
  EXPECT_FALSE(WithinEdgeBounds(1.0 + 1e-12));
  EXPECT_FALSE(WithinEdgeBounds(-1.5));
  const Block block = Fig11Block();
  const Eigen::Matrix3d R = EdgeImpactAttitude(block, 1, 2, 0.1);
  EXPECT_TRUE(EdgeImpact(block, R, 1, 2, Eigen::Vector3d(1, 0, 0), {0.9, 0.0}).within_geometric_bounds);
  EXPECT_FALSE(EdgeImpact(block, R, 1, 2, Eigen::Vector3d(1, 0, 0), {1.2, 0.0}).within_geometric_bounds);
}

TEST(EdgeImpact, RejectsBadArguments) {
  const Block block = Fig11Block();
  const Eigen::Matrix3d R = EdgeImpactAttitude(block, 1, 2, 0.1);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(EdgeImpact(block, R, 1, 3, Eigen::Vector3d(1, 0, 0), {}), InvalidArgument);
  EXPECT_THROW(EdgeImpact(block, R, 1, 2, Eigen::Vector3d(nan, 0, 0), {}), InvalidArgument);
  EXPECT_THROW(EdgeImpact(block, R, 1, 2, Eigen::Vector3d(1, 0, 0), {nan, 0.0}), InvalidArgument);
  EXPECT_THROW(EdgeImpact(block, R, 1, 2, Eigen::Vector3d(1, 0, 0), {1.0, nan}), InvalidArgument);
  EXPECT_THROW(EdgeImpact(block, 2.0 * R, 1, 2, Eigen::Vector3d(1, 0, 0), {}), InvalidArgument);
  EXPECT_THROW(EdgeImpact(block, -R, 1, 2, Eigen::Vector3d(1, 0, 0), {}), InvalidArgument);  // a reflection
  EXPECT_THROW(EdgeImpactSingularLambdas(block, R, 2, 4), InvalidArgument);
}

}  // namespace
}  // namespace rockfit::core
